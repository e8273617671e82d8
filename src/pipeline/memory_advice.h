// One-line messages for a rank that runs out of device memory, saying what would fit: more ranks,
// a smaller --k, a smaller --size. The numbers are estimates from the sizes the renderer allocates
// (docs/RELIABILITY.md shows them against a forced small budget).
#pragma once

#include <cstdint>
#include <string>

#include "compositor/deep_compositor.h"
#include "prep/prepared_rank.h"
#include "vk/context.h"
#include "vk/vk_error.h"

namespace sm::app {

// The scene (element buffers, shell, acceleration structures) did not fit on this rank.
std::string sceneMemoryAdvice(const vk::DeviceMemoryError& e, const vk::Context& ctx,
                              const prep::PreparedRank& rank, int ranks);

// Fragment lists (or the two-pass segment buffer) did not fit beside a scene of sceneBytes.
std::string listMemoryAdvice(const vk::DeviceMemoryError& e, const vk::Context& ctx,
                             uint64_t sceneBytes, int width, int height,
                             const comp::CompositorOptions& lists, int ranks);

}  // namespace sm::app
