#include "vk/pipeline.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <string>

#include "vk/vk_error.h"

namespace sm::vk {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

Specialization::Specialization(const std::vector<SpecConstant>& constants) {
  for (const SpecConstant& c : constants) {
    entries.push_back({c.id, uint32_t(values.size() * sizeof(uint32_t)), sizeof(uint32_t)});
    values.push_back(c.value);
  }
  vk = {uint32_t(entries.size()), entries.data(), values.size() * sizeof(uint32_t), values.data()};
}

DeviceHandle<VkShaderModule> makeShaderModule(const Context& ctx, std::span<const uint32_t> spirv,
                                              const std::string& name) {
  VkShaderModuleCreateInfo smci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  smci.codeSize = spirv.size_bytes();
  smci.pCode = spirv.data();
  VkShaderModule mod;
  SM_VK(vkCreateShaderModule(ctx.device(), &smci, nullptr, &mod));
  ctx.setName(VK_OBJECT_TYPE_SHADER_MODULE, uint64_t(mod), name);
  return DeviceHandle<VkShaderModule>(ctx.device(), mod, vkDestroyShaderModule);
}

PipelineBindings::PipelineBindings(const Context& ctx, VkShaderStageFlags stages,
                                   uint32_t pushConstantBytes, bool accelerationStructure)
    : ctx_(&ctx), stages_(stages) {
  VkDevice dev = ctx.device();
  std::vector<VkDescriptorSetLayout> setLayouts;
  if (accelerationStructure) {
    VkDescriptorSetLayoutBinding b{0, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR, 1, stages,
                                   nullptr};
    VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    lci.bindingCount = 1;
    lci.pBindings = &b;
    VkDescriptorSetLayout sl;
    SM_VK(vkCreateDescriptorSetLayout(dev, &lci, nullptr, &sl));
    setLayout_ = DeviceHandle<VkDescriptorSetLayout>(dev, sl, vkDestroyDescriptorSetLayout);
    setLayouts.push_back(sl);

    VkDescriptorPoolSize ps{VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR, 1};
    VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pci.maxSets = 1;
    pci.poolSizeCount = 1;
    pci.pPoolSizes = &ps;
    VkDescriptorPool pool;
    SM_VK(vkCreateDescriptorPool(dev, &pci, nullptr, &pool));
    pool_ = DeviceHandle<VkDescriptorPool>(dev, pool, vkDestroyDescriptorPool);
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &sl;
    SM_VK(vkAllocateDescriptorSets(dev, &ai, &set_));
  }
  VkPushConstantRange pcr{stages, 0, pushConstantBytes};
  VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  plci.setLayoutCount = uint32_t(setLayouts.size());
  plci.pSetLayouts = setLayouts.data();
  plci.pushConstantRangeCount = pushConstantBytes ? 1 : 0;
  plci.pPushConstantRanges = &pcr;
  VkPipelineLayout pl;
  SM_VK(vkCreatePipelineLayout(dev, &plci, nullptr, &pl));
  layout_ = DeviceHandle<VkPipelineLayout>(dev, pl, vkDestroyPipelineLayout);
}

void PipelineBindings::setAccelerationStructure(VkAccelerationStructureKHR tlas) {
  VkWriteDescriptorSetAccelerationStructureKHR as{
      VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR};
  as.accelerationStructureCount = 1;
  as.pAccelerationStructures = &tlas;
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.pNext = &as;
  w.dstSet = set_;
  w.dstBinding = 0;
  w.descriptorCount = 1;
  w.descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
  vkUpdateDescriptorSets(ctx_->device(), 1, &w, 0, nullptr);
}

void PipelineBindings::bind(VkCommandBuffer cmd, VkPipelineBindPoint point, const void* push,
                            uint32_t pushBytes) const {
  if (set_) vkCmdBindDescriptorSets(cmd, point, layout_.get(), 0, 1, &set_, 0, nullptr);
  if (pushBytes) vkCmdPushConstants(cmd, layout_.get(), stages_, 0, pushBytes, push);
}

ComputePipeline::ComputePipeline(const Context& ctx, const PipelineDesc& d)
    : ctx_(&ctx),
      bindings_(ctx, VK_SHADER_STAGE_COMPUTE_BIT, d.pushConstantBytes, d.accelerationStructure) {
  const auto start = std::chrono::steady_clock::now();
  Specialization spec(d.specialization);
  const PipelineStore& store = ctx.pipelines();
  bool fromCache = false;
  if (store.shaderObjects()) {
    const VkDescriptorSetLayout setLayout = bindings_.setLayout();
    shader_ = store.createComputeShader(
        {d.name, d.spirv, spec.info(),
         setLayout ? std::span(&setLayout, 1) : std::span<const VkDescriptorSetLayout>(),
         d.pushConstantBytes},
        fromCache);
    ctx.setName(VK_OBJECT_TYPE_SHADER_EXT, uint64_t(shader_.get()), d.name);
  } else {
    module_ = makeShaderModule(ctx, d.spirv, d.name);
    VkComputePipelineCreateInfo cci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    cci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    cci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    cci.stage.module = module_.get();
    cci.stage.pName = "main";
    cci.stage.pSpecializationInfo = spec.info();
    cci.layout = bindings_.layout();
    VkPipeline p;
    SM_VK(vkCreateComputePipelines(ctx.device(), store.pipelineCache(), 1, &cci, nullptr, &p));
    pipeline_ = DeviceHandle<VkPipeline>(ctx.device(), p, vkDestroyPipeline);
    ctx.setName(VK_OBJECT_TYPE_PIPELINE, uint64_t(p), d.name);
  }
  store.record({d.name, millisecondsSince(start), fromCache});
}

void ComputePipeline::setAccelerationStructure(VkAccelerationStructureKHR tlas) {
  bindings_.setAccelerationStructure(tlas);
}

void ComputePipeline::dispatch(VkCommandBuffer cmd, uint32_t gx, uint32_t gy, uint32_t gz,
                               const void* push, uint32_t pushBytes) const {
  if (shader_)
    ctx_->pipelines().bindCompute(cmd, shader_.get());
  else
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
  bindings_.bind(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, push, pushBytes);
  if (gx && gy && gz) vkCmdDispatch(cmd, gx, gy, gz);
}

GroupGrid groupGrid(uint64_t groups, uint32_t maxX, uint32_t maxY) {
  if (groups == 0) return {};
  const uint64_t y = maxX ? (groups + maxX - 1) / maxX : UINT64_MAX;
  if (y > maxY)
    throw VulkanError("a dispatch of " + std::to_string(groups) +
                          " workgroups exceeds the device's " + std::to_string(maxX) + " x " +
                          std::to_string(maxY) + " grid",
                      VK_ERROR_UNKNOWN);
  return {uint32_t((groups + y - 1) / y), uint32_t(y)};
}

GroupGrid ComputePipeline::gridFor(uint64_t items, uint32_t itemsPerGroup) const {
  const uint32_t* limit = ctx_->properties().limits.maxComputeWorkGroupCount;
  return groupGrid((items + itemsPerGroup - 1) / itemsPerGroup, std::min(limit[0], kGridRowGroups),
                   limit[1]);
}

TimestampQueries::TimestampQueries(const Context& ctx, uint32_t count) : ctx_(&ctx), count_(count) {
  VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  qci.queryType = VK_QUERY_TYPE_TIMESTAMP;
  qci.queryCount = count;
  VkQueryPool pool;
  SM_VK(vkCreateQueryPool(ctx.device(), &qci, nullptr, &pool));
  pool_ = DeviceHandle<VkQueryPool>(ctx.device(), pool, vkDestroyQueryPool);
}

void TimestampQueries::reset(VkCommandBuffer cmd) {
  vkCmdResetQueryPool(cmd, pool_.get(), 0, count_);
}

void TimestampQueries::write(VkCommandBuffer cmd, uint32_t index) const {
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_.get(), index);
}

std::vector<uint64_t> TimestampQueries::results(uint32_t n) const {
  std::vector<uint64_t> r(n);
  SM_VK(vkGetQueryPoolResults(ctx_->device(), pool_.get(), 0, n, r.size() * sizeof(uint64_t),
                              r.data(), sizeof(uint64_t),
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  return r;
}

double TimestampQueries::ms(const std::vector<uint64_t>& r, uint32_t a, uint32_t b) const {
  return double(r[b] - r[a]) * ctx_->timestampPeriodNs() * 1e-6;
}

}  // namespace sm::vk
