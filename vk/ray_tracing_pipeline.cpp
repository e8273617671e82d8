#include "vk/ray_tracing_pipeline.h"

#include <chrono>
#include <cstring>
#include <memory>

#include "vk/vk_error.h"

namespace sm::vk {
namespace {

constexpr VkShaderStageFlags kTracingStages =
    VK_SHADER_STAGE_RAYGEN_BIT_KHR | VK_SHADER_STAGE_MISS_BIT_KHR |
    VK_SHADER_STAGE_INTERSECTION_BIT_KHR | VK_SHADER_STAGE_ANY_HIT_BIT_KHR |
    VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR;

VkDeviceSize alignUp(VkDeviceSize x, VkDeviceSize a) {
  return (x + a - 1) / a * a;
}

// The create infos of a pipeline's stages and groups, with the storage their pointers reach.
struct StageList {
  std::vector<VkPipelineShaderStageCreateInfo> stages;
  std::vector<VkRayTracingShaderGroupCreateInfoKHR> groups;
  std::vector<std::unique_ptr<Specialization>> specs;

  uint32_t add(VkShaderStageFlagBits stage, VkShaderModule module,
               const std::vector<SpecConstant>& constants) {
    specs.push_back(std::make_unique<Specialization>(constants));
    VkPipelineShaderStageCreateInfo s{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    s.stage = stage;
    s.module = module;
    s.pName = "main";
    s.pSpecializationInfo = specs.back()->info();
    stages.push_back(s);
    return uint32_t(stages.size() - 1);
  }
  void group(VkRayTracingShaderGroupTypeKHR type, uint32_t general, uint32_t closestHit,
             uint32_t anyHit, uint32_t intersection) {
    VkRayTracingShaderGroupCreateInfoKHR g{
        VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR};
    g.type = type;
    g.generalShader = general;
    g.closestHitShader = closestHit;
    g.anyHitShader = anyHit;
    g.intersectionShader = intersection;
    groups.push_back(g);
  }
};

std::vector<SpecConstant> joined(std::vector<SpecConstant> a, const std::vector<SpecConstant>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

}  // namespace

RayTracingPipeline::RayTracingPipeline(const Context& ctx, const RayTracingPipelineDesc& d)
    : ctx_(&ctx), bindings_(ctx, kTracingStages, d.pushConstantBytes, d.accelerationStructure) {
  if (!ctx.hasRayTracingPipeline() || !ctx.fn().createRayTracingPipelines)
    throw VulkanError(d.name + ": " + ctx.deviceName() + " has no ray tracing pipeline enabled",
                      VK_ERROR_FEATURE_NOT_PRESENT);
  auto module = [&](std::span<const uint32_t> spirv, const char* stage) {
    if (spirv.empty()) return VkShaderModule(VK_NULL_HANDLE);
    modules_.push_back(makeShaderModule(ctx, spirv, d.name + " (" + stage + ")"));
    return modules_.back().get();
  };
  StageList list;
  const uint32_t none = VK_SHADER_UNUSED_KHR;
  uint32_t rayGen = list.add(VK_SHADER_STAGE_RAYGEN_BIT_KHR, module(d.rayGen, "ray generation"),
                             d.specialization);
  list.group(VK_RAY_TRACING_SHADER_GROUP_TYPE_GENERAL_KHR, rayGen, none, none, none);
  uint32_t miss = list.add(VK_SHADER_STAGE_MISS_BIT_KHR, module(d.miss, "miss"), d.specialization);
  list.group(VK_RAY_TRACING_SHADER_GROUP_TYPE_GENERAL_KHR, miss, none, none, none);
  VkShaderModule intersection = VK_NULL_HANDLE, anyHit = VK_NULL_HANDLE,
                 closestHit = VK_NULL_HANDLE;
  for (const HitGroupDesc& h : d.hitGroups) {
    // Groups share modules: a module per distinct shader, made the first time.
    if (!h.intersection.empty() && !intersection)
      intersection = module(h.intersection, "intersection");
    if (!h.anyHit.empty() && !anyHit) anyHit = module(h.anyHit, "any hit");
    if (!h.closestHit.empty() && !closestHit) closestHit = module(h.closestHit, "closest hit");
    const auto spec = joined(d.specialization, h.specialization);
    uint32_t is = h.intersection.empty()
                      ? none
                      : list.add(VK_SHADER_STAGE_INTERSECTION_BIT_KHR, intersection, spec);
    uint32_t ah = h.anyHit.empty() ? none : list.add(VK_SHADER_STAGE_ANY_HIT_BIT_KHR, anyHit, spec);
    uint32_t ch = h.closestHit.empty()
                      ? none
                      : list.add(VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR, closestHit, spec);
    list.group(is == none ? VK_RAY_TRACING_SHADER_GROUP_TYPE_TRIANGLES_HIT_GROUP_KHR
                          : VK_RAY_TRACING_SHADER_GROUP_TYPE_PROCEDURAL_HIT_GROUP_KHR,
               none, ch, ah, is);
  }
  VkRayTracingPipelineCreateInfoKHR ci{VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR};
  ci.stageCount = uint32_t(list.stages.size());
  ci.pStages = list.stages.data();
  ci.groupCount = uint32_t(list.groups.size());
  ci.pGroups = list.groups.data();
  ci.maxPipelineRayRecursionDepth = 1;
  ci.layout = bindings_.layout();
  VkPipeline p = VK_NULL_HANDLE;
  const auto start = std::chrono::steady_clock::now();
  // SHELLMARCH_FAIL_RAY_TRACING_PIPELINE=1: the driver's failure, for the tests of its message.
  VkResult made =
      envFlag("SHELLMARCH_FAIL_RAY_TRACING_PIPELINE")
          ? VK_ERROR_INITIALIZATION_FAILED
          : ctx.fn().createRayTracingPipelines(
                ctx.device(), VK_NULL_HANDLE, ctx.pipelines().pipelineCache(), 1, &ci, nullptr, &p);
  if (made != VK_SUCCESS)
    throw VulkanError(ctx.deviceName() + " failed to create the ray tracing pipeline '" + d.name +
                          "' (" + resultName(made) + ")",
                      made);
  pipeline_ = DeviceHandle<VkPipeline>(ctx.device(), p, vkDestroyPipeline);
  ctx.pipelines().record({d.name, millisecondsSince(start), false});
  ctx.setName(VK_OBJECT_TYPE_PIPELINE, uint64_t(p), d.name);
  buildBindingTable(ctx, uint32_t(list.groups.size()), d.name);
}

// Group 0 is the ray generation shader, 1 the miss shader, then the hit groups in order. Each
// region starts at a multiple of shaderGroupBaseAlignment; records are the handle size rounded up
// to shaderGroupHandleAlignment.
void RayTracingPipeline::buildBindingTable(const Context& ctx, uint32_t groups,
                                           const std::string& name) {
  const RayTracingLimits& lim = ctx.rayTracingLimits();
  const uint32_t handle = lim.handleSize;
  std::vector<uint8_t> handles(size_t(groups) * handle);
  SM_VK(ctx.fn().getRayTracingShaderGroupHandles(ctx.device(), pipeline_.get(), 0, groups,
                                                 handles.size(), handles.data()));
  const VkDeviceSize stride = alignUp(handle, lim.handleAlignment);
  const VkDeviceSize base = lim.baseAlignment;
  const uint32_t hitGroups = groups - 2;
  const VkDeviceSize rayGenOffset = 0, missOffset = alignUp(stride, base),
                     hitOffset = missOffset + alignUp(stride, base);
  const VkDeviceSize bytes = hitOffset + stride * hitGroups;
  std::vector<uint8_t> table(bytes, 0);
  auto put = [&](uint32_t group, VkDeviceSize at) {
    std::memcpy(table.data() + at, handles.data() + size_t(group) * handle, handle);
  };
  put(0, rayGenOffset);
  put(1, missOffset);
  for (uint32_t i = 0; i < hitGroups; ++i) put(2 + i, hitOffset + i * stride);
  // The buffer's address need only be aligned to its memory requirements: place the table at the
  // first multiple of the base alignment inside a buffer that much larger.
  table_ = Buffer(ctx, bytes + base,
                  VK_BUFFER_USAGE_SHADER_BINDING_TABLE_BIT_KHR |
                      VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                  MemoryUse::Device, name + " (shader binding table)");
  const VkDeviceAddress start = alignUp(table_.address(), base);
  table_.upload(table.data(), bytes, start - table_.address());
  // The ray generation region's size must equal its stride.
  rayGenRegion_ = {start + rayGenOffset, alignUp(stride, base), alignUp(stride, base)};
  missRegion_ = {start + missOffset, stride, stride};
  hitRegion_ = {start + hitOffset, stride, stride * hitGroups};
}

void RayTracingPipeline::setAccelerationStructure(VkAccelerationStructureKHR tlas) {
  bindings_.setAccelerationStructure(tlas);
}

void RayTracingPipeline::trace(VkCommandBuffer cmd, uint32_t width, uint32_t height,
                               const void* push, uint32_t pushBytes) const {
  constexpr VkAccessFlags kShader = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
  constexpr VkPipelineStageFlags kEarlier =
      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
  memoryBarrier(cmd, kEarlier, VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR, kShader);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipeline_.get());
  bindings_.bind(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, push, pushBytes);
  if (width && height)
    ctx_->fn().cmdTraceRays(cmd, &rayGenRegion_, &missRegion_, &hitRegion_, &callableRegion_, width,
                            height, 1);
  memoryBarrier(cmd, VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR, VK_ACCESS_SHADER_WRITE_BIT,
                kEarlier | VK_PIPELINE_STAGE_HOST_BIT,
                kShader | VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT |
                    VK_ACCESS_HOST_READ_BIT);
}

}  // namespace sm::vk
