// The renderer: a thin facade over the pass objects. One frame = traversal, marching, compositing.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

#include "compositor/deep_compositor.h"
#include "render/gpu_scene.h"
#include "render/preintegration.h"
#include "render/render_passes.h"
#include "render/render_settings.h"

namespace sm::render {

// A ray in world coordinates, for renderRays.
struct WorldRay {
  glm::dvec3 origin;
  glm::dvec3 direction;  // unit length
};

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
  gpu::FrameParams frameParams(const RenderSettings& s) const;
  void renderTwoPass(const RenderSettings& s, gpu::FrameParams& p, FrameResult& out);
  void renderCached(const RenderSettings& s, uint32_t slots, gpu::FrameParams& p, FrameResult& out);
  // Segment cache slots per pixel that s.segmentCacheBytes allows (0: stage-split passes).
  uint32_t segmentCacheSlots(const RenderSettings& s) const;
  void ensureSegments(gpu::FrameParams& p, uint64_t segments);
  // One submission of `record` between timestamps: its device milliseconds.
  double timedDispatch(const std::function<void(VkCommandBuffer)>& record);
  // After a counting pass: prefix sum (the lists), segment storage, parameters for the next pass.
  void scanCounts(gpu::FrameParams& p, FrameResult& out, bool segments);
  // False when the device has no room for a cache of `bytes` (the frame then runs stage-split).
  bool ensureSegmentCache(uint64_t bytes);
  void renderFixed(const RenderSettings& s, gpu::FrameParams& p, FrameResult& out);
  void writeParams(const gpu::FrameParams& p);
  // Checks the planes and writes them, in device coordinates, into p.
  void setClipPlanes(std::span<const scene::ClipPlane> planes, gpu::FrameParams& p) const;

  const vk::Context& ctx_;
  const GpuScene& scene_;
  comp::DeepCompositor& compositor_;
  void updatePreintegration(const RenderSettings& s);
  bool twoPass() const { return compositor_.options().mode == comp::ListMode::TwoPass; }

  std::shared_ptr<PassCache> passes_;  // pipelines per pass and options, built on first use
  PassOptions passOptions_;            // of the frame being rendered
  vk::Buffer preintegration_;
  uint64_t preintegrationKey_ = 0;
  PreintegrationTable preintegrationTable_;
  vk::Buffer params_, stats_, transferFunction_, segments_, segmentCache_, rays_;
  uint64_t lastSegmentTotal_ = 0;
  bool lastSegmentsKept_ = false;  // whether the last frame wrote its segment lists
  uint64_t failedCacheBytes_ = 0;  // the smallest segment cache the device had no room for
  bool useRays_ = false;
  vk::TimestampQueries timestamps_;
};

}  // namespace sm::render
