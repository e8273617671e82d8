// How a frame fills the compositor's fragment lists, one strategy object per list mode:
//   - StageSplitLists (two-pass lists): count each pixel's segments, scan, store them, march them;
//     traversal runs twice and is timed apart from marching.
//   - CachedLists (two-pass lists, when the segment cache fits): trace and march once, caching
//     each pixel's first segments, scan, then copy them into the lists.
//   - FixedLists (fixed-size lists): trace, march and write in one pass.
// Renderer picks one per frame (cachedFits decides between the two two-pass strategies) and then
// composites; each strategy times its own passes into FrameResult::timings.
#pragma once

#include <cstdint>

#include "compositor/deep_compositor.h"
#include "render/frame_resources.h"
#include "render/frame_result.h"
#include "render/render_passes.h"
#include "render/render_settings.h"

namespace sm::render {

// What a strategy works with for one frame.
struct FrameWork {
  const vk::Context& ctx;
  comp::DeepCompositor& compositor;
  PassCache& passes;
  FrameResources& resources;
  PassOptions options;
  const RenderSettings& settings;
  gpu::FrameParams& params;
  FrameResult& out;
};

class ListStrategy {
 public:
  virtual ~ListStrategy() = default;
  // Writes this frame's fragments into the compositor's lists (params already checked).
  virtual void fill(FrameWork& f) const = 0;
};

class StageSplitLists final : public ListStrategy {
 public:
  void fill(FrameWork& f) const override;
};

class CachedLists final : public ListStrategy {
 public:
  // Cache slots per pixel that the settings and the device allow (0: none). The cache takes at
  // most an eighth of the device (the lists and the scene need the rest).
  static uint32_t slots(const vk::Context& ctx, const RenderSettings& s);
  // Whether this frame can run cached: some slots, and room on the device for them.
  static bool fits(const vk::Context& ctx, FrameResources& resources, const RenderSettings& s);
  void fill(FrameWork& f) const override;
};

class FixedLists final : public ListStrategy {
 public:
  void fill(FrameWork& f) const override;
};

}  // namespace sm::render
