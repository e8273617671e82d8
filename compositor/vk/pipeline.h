// Compute pipelines built from embedded SPIR-V, specialised to the scene with specialization
// constants, parameters passed as push constants
// (buffer addresses and small values). A pipeline that traces rays owns one descriptor set with the
// top-level acceleration structure at set 0, binding 0.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "vk/context.h"

namespace sm::vk {

struct SpecConstant {
  uint32_t id;     // constant_id in the shader
  uint32_t value;  // 32-bit (bool: 0 or 1)
};

struct PipelineDesc {
  std::string name;
  std::span<const uint32_t> spirv;
  std::vector<SpecConstant> specialization;
  uint32_t pushConstantBytes = 0;
  bool accelerationStructure = false;  // set 0, binding 0
};

class ComputePipeline {
 public:
  ComputePipeline() = default;
  ComputePipeline(const Context& ctx, const PipelineDesc& desc);
  ComputePipeline(ComputePipeline&&) noexcept = default;
  ComputePipeline& operator=(ComputePipeline&&) noexcept = default;

  void setAccelerationStructure(VkAccelerationStructureKHR tlas);
  // Binds, pushes constants and dispatches groups (x, y, z).
  void dispatch(VkCommandBuffer cmd, uint32_t gx, uint32_t gy, uint32_t gz, const void* push,
                uint32_t pushBytes) const;
  template <typename T>
  void dispatch(VkCommandBuffer cmd, uint32_t gx, uint32_t gy, uint32_t gz, const T& push) const {
    dispatch(cmd, gx, gy, gz, &push, sizeof(T));
  }
  bool valid() const { return bool(pipeline_); }

 private:
  const Context* ctx_ = nullptr;
  DeviceHandle<VkShaderModule> module_;
  DeviceHandle<VkDescriptorSetLayout> setLayout_;
  DeviceHandle<VkPipelineLayout> layout_;
  DeviceHandle<VkPipeline> pipeline_;
  DeviceHandle<VkDescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  uint32_t pushBytes_ = 0;
};

inline uint32_t groupsFor(uint64_t items, uint32_t groupSize) {
  return uint32_t((items + groupSize - 1) / groupSize);
}

// GPU timestamps for per-stage timing.
class TimestampQueries {
 public:
  TimestampQueries() = default;
  TimestampQueries(const Context& ctx, uint32_t count);
  void reset(VkCommandBuffer cmd);
  void write(VkCommandBuffer cmd, uint32_t index) const;
  // The first n timestamps (all written by completed work); ms() between two of them.
  std::vector<uint64_t> results(uint32_t n) const;
  double ms(const std::vector<uint64_t>& r, uint32_t a, uint32_t b) const;

 private:
  const Context* ctx_ = nullptr;
  DeviceHandle<VkQueryPool> pool_;
  uint32_t count_ = 0;
};

}  // namespace sm::vk
