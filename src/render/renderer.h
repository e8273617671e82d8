// The renderer: a thin facade. One frame = its parameters (frame_params.h), the list mode's passes
// (list_modes.h) over the frame's buffers (frame_resources.h), then compositing.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec4.hpp>

#include "compositor/deep_compositor.h"
#include "render/frame_resources.h"
#include "render/frame_result.h"
#include "render/gpu_scene.h"
#include "render/list_modes.h"
#include "render/render_passes.h"
#include "render/render_settings.h"

namespace sm::render {

// A ray in world coordinates, for renderRays.
struct WorldRay {
  glm::dvec3 origin;
  glm::dvec3 direction;  // unit length
};

class Renderer {
 public:
  // `passes`: the pipelines of an earlier renderer of this scene, shared when they serve this
  // compositor's lists and tracer (PassCache); otherwise, and by default, the renderer builds its
  // own. `tracer`: how shell crossings are traced (Auto: the context's choice, ctx.tracer()).
  Renderer(const vk::Context& ctx, const GpuScene& scene, comp::DeepCompositor& compositor,
           std::shared_ptr<PassCache> passes = nullptr, vk::Tracer tracer = vk::Tracer::Auto);
  // The tracer this renderer's frames use (Query or Pipeline).
  vk::Tracer tracer() const { return passes_->tracer(); }
  // `reuse`: an earlier frame's pixels, whose storage this frame's image takes over. A frame loop
  // hands each frame's pixels back (`frame = r.render(s, std::move(frame.pixels))`): a fresh
  // image per frame costs its page faults every frame once it is over glibc's 32 MiB mapping
  // threshold (1448² and up), 35 ms at 2048² on the benchmark machine.
  FrameResult render(const RenderSettings& settings, std::vector<glm::vec4> reuse = {});
  // Renders explicit rays (world coordinates) instead of camera rays: ray i is pixel (i, 0) of a
  // rays.size() x 1 image (the compositor must have that size). For tests aiming at vertices/edges.
  FrameResult renderRays(const RenderSettings& settings, const std::vector<WorldRay>& rays);
  // The pipelines this renderer uses, to hand to the next renderer of the same scene.
  const std::shared_ptr<PassCache>& passes() const { return passes_; }
  // Per-pixel counts of the last frame on this rank (statistics and heatmaps).
  std::vector<uint32_t> lastSegmentCounts() const;
  std::vector<uint32_t> lastFragmentCounts() const;
  // The segments traversal found in the last two-pass frame, per pixel (for tests that compare
  // segment lists with the CPU reference); empty after a cached frame without keepSegments.
  std::vector<std::vector<gpu::Segment>> lastSegments() const;
  // This rank's fragments of the last frame per pixel, in list order (decoded to floats).
  std::vector<std::vector<comp::DcFragment>> lastFragments() const;

 private:
  FrameResult renderFrame(const RenderSettings& s, std::vector<glm::vec4> reuse, bool explicitRays);
  bool twoPass() const { return compositor_.options().mode == comp::ListMode::TwoPass; }
  const ListStrategy& strategyFor(const RenderSettings& s);

  const vk::Context& ctx_;
  const GpuScene& scene_;
  comp::DeepCompositor& compositor_;
  std::shared_ptr<PassCache> passes_;  // pipelines per pass and options, built on first use
  FrameResources resources_;
  StageSplitLists stageSplit_;
  CachedLists cached_;
  FixedLists fixed_;
};

}  // namespace sm::render
