// Per-frame outputs beyond the image: the single-fragment vs deep comparison heatmap and the
// per-rank fragment-count heatmaps (the paper's figures). Both are collective: every rank calls.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "comm/reductions.h"
#include "compositor/deep_compositor.h"

namespace sm::app {

struct RenderJob;

// Path for step `step` of a sequence ("out.png" -> "out_0003.png"); `path` itself for one frame.
std::string framePath(const std::string& path, uint64_t step, bool sequence);

// The combined fragment-count heatmap of --heatmaps PREFIX (the per-rank ones sit beside it).
std::string combinedHeatmapPath(const std::string& prefix);

void writeFrameExtras(const RenderJob& job, comp::DeepCompositor& compositor,
                      const std::vector<glm::vec4>& image, uint64_t step, bool sequence,
                      comm::Communicator& comm);

}  // namespace sm::app
