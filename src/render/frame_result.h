// What one frame returns: the image (rank 0), the device counters, and where its time went.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "compositor/deep_compositor.h"
#include "shared/render_types.h"

namespace sm::render {

struct FrameTimings {
  // Stage-split two-pass frames time traversal (both passes) and marching apart. Where the two
  // are fused (`fused`: cached two-pass lists, fixed lists) traversalMs is the pass that traces
  // and marches, and marchMs the cached store pass (0 for fixed lists).
  double traversalMs = 0;
  double scanMs = 0;  // prefix sum over the counts, and the host round trip for the total
  double marchMs = 0;
  bool fused = false;
  double compositeMs = 0;
  double totalMs = 0;  // wall clock of render()
};

struct FrameResult {
  std::vector<glm::vec4> pixels;  // premultiplied RGBA, row 0 at the top; rank 0 only
  gpu::RenderStats counters{};
  FrameTimings timings;
  uint64_t segments = 0;           // segments found this frame on this rank
  uint64_t fragments = 0;          // fragments written this frame on this rank
  comp::CompositeStats composite;  // this rank's share of compositing
};

}  // namespace sm::render
