#include "vk/pipeline_store.h"

#include <cstdio>
#include <cstring>

#include "vk/vk_error.h"

namespace sm::vk {
namespace {

std::string hex(uint64_t v, int digits) {
  char s[17];
  std::snprintf(s, sizeof s, "%0*llx", digits, (unsigned long long)v);
  return s;
}

uint64_t identityHash(const CacheIdentity& id) {
  return fnv1a({reinterpret_cast<const uint8_t*>(&id), sizeof id});
}

template <typename T>
uint64_t hashOf(std::span<const T> values, uint64_t seed) {
  return fnv1a({reinterpret_cast<const uint8_t*>(values.data()), values.size_bytes()}, seed);
}

// The key of a compute shader: everything the driver compiles it from.
uint64_t shaderKey(const ComputeShaderDesc& d) {
  uint64_t h = hashOf(d.spirv, fnv1a({reinterpret_cast<const uint8_t*>("compute"), 7}));
  if (const VkSpecializationInfo* s = d.specialization) {
    h = hashOf(std::span(s->pMapEntries, s->mapEntryCount), h);
    h = fnv1a({static_cast<const uint8_t*>(s->pData), s->dataSize}, h);
  }
  const uint32_t iface[2] = {uint32_t(d.setLayouts.size()), d.pushConstantBytes};
  return hashOf(std::span<const uint32_t>(iface), h);
}

}  // namespace

PipelineStore::PipelineStore(VkPhysicalDevice physical, VkDevice device, std::string folder,
                             bool shaderObjects)
    : device_(device), files_(std::move(folder)), shaderObjects_(shaderObjects) {
  VkPhysicalDeviceShaderObjectPropertiesEXT so{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_OBJECT_PROPERTIES_EXT};
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2,
                                 shaderObjects ? &so : nullptr};
  vkGetPhysicalDeviceProperties2(physical, &p2);
  const VkPhysicalDeviceProperties& p = p2.properties;
  std::memcpy(pipelineIdentity_.uuid, p.pipelineCacheUUID, VK_UUID_SIZE);
  pipelineIdentity_.version = p.driverVersion;
  pipelineIdentity_.vendorId = binaryIdentity_.vendorId = p.vendorID;
  pipelineIdentity_.deviceId = binaryIdentity_.deviceId = p.deviceID;
  if (shaderObjects) {
    std::memcpy(binaryIdentity_.uuid, so.shaderBinaryUUID, VK_UUID_SIZE);
    binaryIdentity_.version = so.shaderBinaryVersion;
    auto load = [&](auto& fn, const char* name) {
      fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(
          vkGetDeviceProcAddr(device, name));
      if (!fn) throw VulkanError(std::string("the driver offers no ") + name, VK_ERROR_UNKNOWN);
    };
    load(createShaders_, "vkCreateShadersEXT");
    load(destroyShader_, "vkDestroyShaderEXT");
    load(getBinary_, "vkGetShaderBinaryDataEXT");
    load(bindShaders_, "vkCmdBindShadersEXT");
  }
  loadPipelineCache();
}

PipelineStore::~PipelineStore() {
  if (!pipelineCache_) return;
  size_t n = 0;
  if (vkGetPipelineCacheData(device_, pipelineCache_, &n, nullptr) == VK_SUCCESS &&
      n > pipelineCacheLoadedBytes_) {
    std::vector<uint8_t> data(n);
    if (vkGetPipelineCacheData(device_, pipelineCache_, &n, data.data()) == VK_SUCCESS)
      files_.store(pipelineCacheName(), ShaderCache::kPipelineCache, pipelineIdentity_, 0,
                   {data.data(), n});
  }
  vkDestroyPipelineCache(device_, pipelineCache_, nullptr);
}

std::string PipelineStore::pipelineCacheName() const {
  return "pipelines-" + hex(identityHash(pipelineIdentity_), 16) + ".bin";
}

void PipelineStore::loadPipelineCache() {
  std::vector<uint8_t> data =
      files_.load(pipelineCacheName(), ShaderCache::kPipelineCache, pipelineIdentity_, 0);
  VkPipelineCacheCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  ci.initialDataSize = data.size();
  ci.pInitialData = data.empty() ? nullptr : data.data();
  if (vkCreatePipelineCache(device_, &ci, nullptr, &pipelineCache_) != VK_SUCCESS) {
    // The driver refused data that passed our checks: start empty rather than fail.
    ci.initialDataSize = 0;
    ci.pInitialData = nullptr;
    data.clear();
    SM_VK(vkCreatePipelineCache(device_, &ci, nullptr, &pipelineCache_));
  }
  pipelineCacheLoadedBytes_ = data.size();
}

DeviceHandle<VkShaderEXT> PipelineStore::createComputeShader(const ComputeShaderDesc& d,
                                                             bool& fromCache) const {
  if (!shaderObjects_)
    throw VulkanError(d.name + ": shader objects are not enabled", VK_ERROR_FEATURE_NOT_PRESENT);
  VkPushConstantRange pcr{VK_SHADER_STAGE_COMPUTE_BIT, 0, d.pushConstantBytes};
  VkShaderCreateInfoEXT ci{VK_STRUCTURE_TYPE_SHADER_CREATE_INFO_EXT};
  ci.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  ci.pName = "main";
  ci.setLayoutCount = uint32_t(d.setLayouts.size());
  ci.pSetLayouts = d.setLayouts.data();
  ci.pushConstantRangeCount = d.pushConstantBytes ? 1 : 0;
  ci.pPushConstantRanges = &pcr;
  ci.pSpecializationInfo = d.specialization;
  const uint64_t key = shaderKey(d);
  const std::string name =
      "shader-" + hex(identityHash(binaryIdentity_), 16) + "-" + hex(key, 16) + ".bin";
  VkShaderEXT shader = VK_NULL_HANDLE;
  fromCache = false;
  std::vector<uint8_t> binary = files_.load(name, ShaderCache::kShaderBinary, binaryIdentity_, key);
  if (!binary.empty()) {
    ci.codeType = VK_SHADER_CODE_TYPE_BINARY_EXT;
    ci.codeSize = binary.size();
    ci.pCode = binary.data();
    // A binary the driver declines (VK_INCOMPATIBLE_SHADER_BINARY_EXT) is compiled again.
    fromCache = createShaders_(device_, 1, &ci, nullptr, &shader) == VK_SUCCESS && shader;
  }
  if (!fromCache) {
    ci.codeType = VK_SHADER_CODE_TYPE_SPIRV_EXT;
    ci.codeSize = d.spirv.size_bytes();
    ci.pCode = d.spirv.data();
    shader = VK_NULL_HANDLE;
    VkResult r = createShaders_(device_, 1, &ci, nullptr, &shader);
    if (r != VK_SUCCESS) throw VulkanError(d.name + ": vkCreateShadersEXT", r);
    size_t n = 0;
    if (files_.enabled() && getBinary_(device_, shader, &n, nullptr) == VK_SUCCESS && n) {
      binary.resize(n);
      if (getBinary_(device_, shader, &n, binary.data()) == VK_SUCCESS)
        files_.store(name, ShaderCache::kShaderBinary, binaryIdentity_, key, {binary.data(), n});
    }
  }
  return DeviceHandle<VkShaderEXT>(device_, shader, destroyShader_);
}

void PipelineStore::bindCompute(VkCommandBuffer cmd, VkShaderEXT shader) const {
  const VkShaderStageFlagBits stage = VK_SHADER_STAGE_COMPUTE_BIT;
  bindShaders_(cmd, 1, &stage, &shader);
}

void PipelineStore::record(PipelineTiming t) const {
  std::lock_guard lock(mutex_);
  timings_.push_back(std::move(t));
}

std::vector<PipelineTiming> PipelineStore::timings() const {
  std::lock_guard lock(mutex_);
  return timings_;
}

}  // namespace sm::vk
