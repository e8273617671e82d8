// The pipeline of one tracer pass (tracer_passes.glsl): a compute pipeline whose shader traces
// with ray queries (tracer.comp), or a ray tracing pipeline whose ray generation shader traces with
// traceRayEXT (tracer.rgen, with shell_hit.rint/.rahit/.rchit). Both run the same passes of the
// same shader library on the same pixels, so they give the same images bit for bit.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "render/gpu_scene.h"
#include "vk/pipeline.h"
#include "vk/ray_tracing_pipeline.h"

namespace sm::render {

class TracerPipeline {
 public:
  // `specialization`: the pass's (sceneSpecialization and the pass constant). `tracer` must be one
  // the context has enabled (Query or Pipeline).
  TracerPipeline(const vk::Context& ctx, const GpuScene& scene, vk::Tracer tracer,
                 const std::string& name, std::vector<vk::SpecConstant> specialization);
  // Traces every pixel of a width x height image; `store` is the two-pass passes' count (0) or
  // store (1) pass.
  void record(VkCommandBuffer cmd, VkDeviceAddress params, int width, int height,
              uint32_t store) const;
  vk::Tracer tracer() const { return tracer_; }

 private:
  vk::Tracer tracer_;
  uint64_t maxInvocations_ = 0;
  vk::ComputePipeline compute_;
  vk::RayTracingPipeline rayTracing_;
};

// The push constants of every tracer and marching pass.
struct TracerPush {
  uint64_t params;
  uint32_t store = 0;  // two-pass passes: 0 count, 1 store
};

}  // namespace sm::render
