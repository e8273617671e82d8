// Compute pipelines built from embedded SPIR-V, specialised to the scene with specialization
// constants, parameters passed as push constants. On CPU devices with VK_EXT_shader_object a
// "pipeline" is a compute shader object whose binary is kept between processes (pipeline_store.h)
// (buffer addresses and small values). A pipeline that traces rays owns one descriptor set with the
// top-level acceleration structure at set 0, binding 0 (ray_tracing_pipeline.h: the same for ray
// tracing pipelines).
#pragma once

#include <chrono>
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

// A shader's specialisation, in the form Vulkan takes (pointers into this object: keep it alive
// and in place while the pipeline is created).
struct Specialization {
  explicit Specialization(const std::vector<SpecConstant>& constants);
  Specialization(const Specialization&) = delete;
  const VkSpecializationInfo* info() const { return entries.empty() ? nullptr : &vk; }
  std::vector<VkSpecializationMapEntry> entries;
  std::vector<uint32_t> values;
  VkSpecializationInfo vk{};
};

// What every pipeline of the renderer binds: push constants and, for a pipeline that traces
// rays, one descriptor set holding the top-level acceleration structure (set 0, binding 0).
class PipelineBindings {
 public:
  PipelineBindings() = default;
  PipelineBindings(const Context& ctx, VkShaderStageFlags stages, uint32_t pushConstantBytes,
                   bool accelerationStructure);
  VkPipelineLayout layout() const { return layout_.get(); }
  VkDescriptorSetLayout setLayout() const { return setLayout_.get(); }
  void setAccelerationStructure(VkAccelerationStructureKHR tlas);
  // Binds the descriptor set (if any) and pushes `pushBytes` of constants.
  void bind(VkCommandBuffer cmd, VkPipelineBindPoint point, const void* push,
            uint32_t pushBytes) const;

 private:
  const Context* ctx_ = nullptr;
  VkShaderStageFlags stages_ = 0;
  DeviceHandle<VkDescriptorSetLayout> setLayout_;
  DeviceHandle<VkPipelineLayout> layout_;
  DeviceHandle<VkDescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

// A shader module of `spirv`, debug-named.
DeviceHandle<VkShaderModule> makeShaderModule(const Context& ctx, std::span<const uint32_t> spirv,
                                              const std::string& name);

// For the startup statistics (PipelineStore::record).
double millisecondsSince(std::chrono::steady_clock::time_point start);

inline uint32_t groupsFor(uint64_t items, uint32_t groupSize) {
  return uint32_t((items + groupSize - 1) / groupSize);
}

// Groups of a one-dimensional dispatch, in rows of at most maxX. Why: a device need take no more
// than 65 535 groups in a dimension (lavapipe and most desktop drivers take no more), and a 2048²
// image at 64 pixels per group is 65 536. y rows of x groups, with the fewest rows and then
// the shortest rows that hold `groups`: fewer than y groups are left idle. Throws VulkanError when
// even maxY rows do not hold them.
//
// Pipelines lay out their dispatches in rows of at most kGridRowGroups even where the device takes
// more (NVIDIA takes 2^31 - 1 in x): every device then runs the same grid, so the rows that
// lavapipe needs are also what a GPU runs and what the tests cover on it.
inline constexpr uint32_t kGridRowGroups = 65535;
struct GroupGrid {
  uint32_t x = 0, y = 0;
};
GroupGrid groupGrid(uint64_t groups, uint32_t maxX, uint32_t maxY);

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
  // A one-dimensional dispatch of `items` work items, `itemsPerGroup` per group, laid out in rows
  // (groupGrid): the shader numbers its groups with smGroupIndex (dispatch_grid.glsl) and
  // returns past the last item.
  template <typename T>
  void dispatchItems(VkCommandBuffer cmd, uint64_t items, uint32_t itemsPerGroup,
                     const T& push) const {
    GroupGrid g = gridFor(items, itemsPerGroup);
    dispatch(cmd, g.x, g.y, 1, &push, sizeof(T));
  }
  bool valid() const { return bool(pipeline_) || bool(shader_); }

 private:
  GroupGrid gridFor(uint64_t items, uint32_t itemsPerGroup) const;

  const Context* ctx_ = nullptr;
  DeviceHandle<VkShaderModule> module_;
  PipelineBindings bindings_;
  DeviceHandle<VkPipeline> pipeline_;  // or, where the context makes shader objects:
  DeviceHandle<VkShaderEXT> shader_;
};

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
