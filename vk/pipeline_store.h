// How a context's pipelines are compiled and kept between processes, and what compiling them cost
// (docs/ARCHITECTURE.md, "Startup").
//
// On every device the driver's VkPipelineCache is loaded from the cache folder when the context
// is made and written back when it goes, if it grew. Lavapipe keeps nothing in it (its data is a
// 32-byte header), and creating the renderer's tracer pipeline costs it seconds in every process
// although Mesa's disk cache holds the machine code: the time goes to the driver's front end.
// On CPU devices with VK_EXT_shader_object, compute shaders are therefore shader objects whose
// binaries (the shader after that front end) are stored per shader and specialisation and
// handed back next time: 2.7 s become 40 ms for the tracer. GPUs keep pipelines: their drivers
// cache compiled pipelines themselves.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/handle.h"
#include "vk/shader_cache.h"
#include "vk/shader_object_ext.h"

namespace sm::vk {

// One pipeline's creation: its name, milliseconds, and whether a stored binary or the driver's
// cache served it.
struct PipelineTiming {
  std::string name;
  double ms = 0;
  bool fromCache = false;
};

// What a compute shader object is made from: SPIR-V, specialisation and the interface it is used
// with (a pipeline layout of these set layouts and push constants).
struct ComputeShaderDesc {
  std::string name;
  std::span<const uint32_t> spirv;
  const VkSpecializationInfo* specialization = nullptr;
  std::span<const VkDescriptorSetLayout> setLayouts;
  uint32_t pushConstantBytes = 0;
};

class PipelineStore {
 public:
  // `folder`: ShaderCache's; "" for none. `shaderObjects`: compute shaders as shader objects (the
  // device has the extension enabled).
  PipelineStore(VkPhysicalDevice physical, VkDevice device, std::string folder, bool shaderObjects);
  ~PipelineStore();  // writes the pipeline cache back where it grew
  PipelineStore(const PipelineStore&) = delete;
  PipelineStore& operator=(const PipelineStore&) = delete;

  VkPipelineCache pipelineCache() const { return pipelineCache_; }
  bool shaderObjects() const { return shaderObjects_; }
  const ShaderCache& files() const { return files_; }

  // A compute shader object, from its stored binary where there is a usable one, else compiled
  // (and its binary stored). `fromCache` says which. Throws VulkanError naming it on failure.
  DeviceHandle<VkShaderEXT> createComputeShader(const ComputeShaderDesc& desc,
                                                bool& fromCache) const;
  void bindCompute(VkCommandBuffer cmd, VkShaderEXT shader) const;

  void record(PipelineTiming t) const;
  std::vector<PipelineTiming> timings() const;

 private:
  void loadPipelineCache();
  std::string pipelineCacheName() const;

  VkDevice device_;
  ShaderCache files_;
  CacheIdentity pipelineIdentity_, binaryIdentity_;
  VkPipelineCache pipelineCache_ = VK_NULL_HANDLE;
  size_t pipelineCacheLoadedBytes_ = 0;
  bool shaderObjects_ = false;
  PFN_vkCreateShadersEXT createShaders_ = nullptr;
  PFN_vkDestroyShaderEXT destroyShader_ = nullptr;
  PFN_vkGetShaderBinaryDataEXT getBinary_ = nullptr;
  PFN_vkCmdBindShadersEXT bindShaders_ = nullptr;
  mutable std::mutex mutex_;
  mutable std::vector<PipelineTiming> timings_;
};

}  // namespace sm::vk
