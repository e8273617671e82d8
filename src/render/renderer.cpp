#include "render/renderer.h"

#include <glm/geometric.hpp>

#include "common/timer.h"
#include "render/frame_params.h"
#include "render/step_limits.h"

namespace sm::render {

Renderer::Renderer(const vk::Context& ctx, const GpuScene& scene, comp::DeepCompositor& compositor,
                   std::shared_ptr<PassCache> passes, vk::Tracer tracer)
    : ctx_(ctx),
      scene_(scene),
      compositor_(compositor),
      passes_(passes && passes->serves(scene, compositor, tracer)
                  ? std::move(passes)
                  : std::make_shared<PassCache>(ctx, scene, compositor, tracer)),
      resources_(ctx) {}

FrameResult Renderer::render(const RenderSettings& s, std::vector<glm::vec4> reuse) {
  return renderFrame(s, std::move(reuse), false);
}

FrameResult Renderer::renderRays(const RenderSettings& settings,
                                 const std::vector<WorldRay>& rays) {
  std::vector<gpu::RayDesc> rebased(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    rebased[i] = {glm::vec3(scene_.toDevice(rays[i].origin)), glm::vec3(rays[i].direction)};
    // Each ray measures t from its own origin, in units of its direction's length.
    checkStep(settings.dt * scene_.scale() * glm::length(rays[i].direction),
              scene_.toDevice(rays[i].origin), scene_.rebasedBounds());
  }
  resources_.setRays(rebased);
  RenderSettings s = settings;
  s.width = int(rebased.size());
  s.height = 1;
  return renderFrame(s, {}, true);
}

// Two-pass lists run cached where the cache fits and stage-split otherwise (the same image).
const ListStrategy& Renderer::strategyFor(const RenderSettings& s) {
  if (!twoPass()) return fixed_;
  if (CachedLists::fits(ctx_, resources_, s)) return cached_;
  return stageSplit_;
}

FrameResult Renderer::renderFrame(const RenderSettings& s, std::vector<glm::vec4> reuse,
                                  bool explicitRays) {
  const Timer total;
  scene::checkScale(s.transferFunction);
  const bool exact = s.integration == Integration::ElementExact;
  resources_.setTransferFunction(s.transferFunction, scene_.scale(), exact);
  gpu::FrameParams params = frameParams(s, scene_, compositor_, resources_, explicitRays);
  resources_.resetStats();
  FrameResult out;
  FrameWork work{ctx_,
                 compositor_,
                 *passes_,
                 resources_,
                 PassOptions{exact, s.shading.enabled, s.allTypePipelines, !s.clipPlanes.empty(),
                             s.transferFunction.scale == scene::ScalarScale::Log},
                 s,
                 params,
                 out};
  strategyFor(s).fill(work);
  const Timer composite;
  out.pixels = std::move(reuse);
  compositor_.composite(s.compositeMethod, out.pixels);
  out.composite = compositor_.stats();
  out.timings.compositeMs = composite.ms();
  out.counters = resources_.readStats();
  out.fragments = out.counters.fragments;
  out.timings.totalMs = total.ms();
  return out;
}

std::vector<uint32_t> Renderer::lastSegmentCounts() const {
  if (!twoPass()) return {};
  std::vector<uint32_t> v(uint64_t(compositor_.width()) * compositor_.height());
  compositor_.downloadCapacities(v);
  return v;
}

std::vector<std::vector<gpu::Segment>> Renderer::lastSegments() const {
  std::vector<std::vector<gpu::Segment>> out;
  if (!twoPass() || !resources_.lastSegmentsKept()) return out;
  const std::vector<gpu::Segment> all = resources_.lastSegments();
  const std::vector<uint32_t> counts = lastSegmentCounts();
  out.resize(counts.size());
  uint64_t at = 0;
  for (size_t p = 0; p < counts.size(); ++p) {
    out[p].assign(all.begin() + at, all.begin() + at + counts[p]);
    at += counts[p];
  }
  return out;
}

std::vector<std::vector<comp::DcFragment>> Renderer::lastFragments() const {
  return compositor_.downloadLists();
}

std::vector<uint32_t> Renderer::lastFragmentCounts() const {
  std::vector<uint32_t> v(uint64_t(compositor_.width()) * compositor_.height());
  compositor_.downloadCounts(v);
  return v;
}

}  // namespace sm::render
