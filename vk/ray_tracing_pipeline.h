// Ray tracing pipelines (VK_KHR_ray_tracing_pipeline) built from embedded SPIR-V: one ray
// generation shader, one miss shader and hit groups, with the shader binding table laid out from
// the device's handle size and alignments. Specialisation, push constants and the acceleration
// structure binding work as for compute pipelines (pipeline.h), so the renderer drives either
// kind of tracer the same way. Recursion depth 1: hit shaders trace no rays.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/pipeline.h"

namespace sm::vk {

// A hit group: intersection and any-hit shaders for procedural (box) geometry, or a closest-hit
// shader for triangles. `specialization` is added to the pipeline's for this group's shaders only
// (the same module may serve two groups specialised differently).
struct HitGroupDesc {
  std::span<const uint32_t> intersection, anyHit, closestHit;
  std::vector<SpecConstant> specialization;
};

struct RayTracingPipelineDesc {
  std::string name;
  std::span<const uint32_t> rayGen, miss;
  std::vector<HitGroupDesc> hitGroups;
  std::vector<SpecConstant> specialization;  // every shader's
  uint32_t pushConstantBytes = 0;            // seen by every stage
  bool accelerationStructure = true;         // set 0, binding 0
};

class RayTracingPipeline {
 public:
  RayTracingPipeline() = default;
  // Throws VulkanError naming the device when the driver fails to create the pipeline (as it does
  // for every pipeline with SHELLMARCH_FAIL_RAY_TRACING_PIPELINE=1, for tests).
  RayTracingPipeline(const Context& ctx, const RayTracingPipelineDesc& desc);
  RayTracingPipeline(RayTracingPipeline&&) noexcept = default;
  RayTracingPipeline& operator=(RayTracingPipeline&&) noexcept = default;

  void setAccelerationStructure(VkAccelerationStructureKHR tlas);
  // Binds, pushes constants and traces a width x height launch. Barriers on either side order it
  // after earlier compute and transfer work and before later compute, transfer and host reads, so
  // that callers order it like a compute dispatch.
  void trace(VkCommandBuffer cmd, uint32_t width, uint32_t height, const void* push,
             uint32_t pushBytes) const;
  template <typename T>
  void trace(VkCommandBuffer cmd, uint32_t width, uint32_t height, const T& push) const {
    trace(cmd, width, height, &push, sizeof(T));
  }
  bool valid() const { return bool(pipeline_); }

 private:
  void buildBindingTable(const Context& ctx, uint32_t groups, const std::string& name);

  const Context* ctx_ = nullptr;
  std::vector<DeviceHandle<VkShaderModule>> modules_;
  PipelineBindings bindings_;
  DeviceHandle<VkPipeline> pipeline_;
  Buffer table_;
  VkStridedDeviceAddressRegionKHR rayGenRegion_{}, missRegion_{}, hitRegion_{}, callableRegion_{};
};

}  // namespace sm::vk
