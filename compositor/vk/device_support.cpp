#include "vk/device_support.h"

#include <algorithm>
#include <cstring>

namespace sm::vk {

std::vector<const char*> requiredDeviceExtensions(const ContextOptions& o) {
  std::vector<const char*> ext;
  if (o.requireRayQuery) {
    ext.push_back(VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME);
    ext.push_back(VK_KHR_RAY_QUERY_EXTENSION_NAME);
    ext.push_back(VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME);
  }
  if (o.swapchain) ext.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  return ext;
}

bool hasExtension(VkPhysicalDevice pd, const char* name) {
  uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> ext(n);
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, ext.data());
  return std::any_of(ext.begin(), ext.end(),
                     [&](auto& e) { return std::strcmp(e.extensionName, name) == 0; });
}

std::vector<std::string> missingFor(VkPhysicalDevice pd, const ContextOptions& o) {
  std::vector<std::string> missing;
  VkPhysicalDeviceProperties p;
  vkGetPhysicalDeviceProperties(pd, &p);
  if (p.apiVersion < VK_API_VERSION_1_2) missing.push_back("Vulkan 1.2");
  for (const char* e : requiredDeviceExtensions(o))
    if (!hasExtension(pd, e)) missing.push_back(e);
  if (!missing.empty()) return missing;
  FeatureChain fc(o.requireRayQuery);
  vkGetPhysicalDeviceFeatures2(pd, &fc.f2);
  if (!fc.v12.bufferDeviceAddress) missing.push_back("bufferDeviceAddress");
  if (!fc.v12.scalarBlockLayout) missing.push_back("scalarBlockLayout");
  if (!fc.f2.features.shaderInt64) missing.push_back("shaderInt64");
  if (o.requireRayQuery && !fc.as.accelerationStructure) missing.push_back("accelerationStructure");
  if (o.requireRayQuery && !fc.rq.rayQuery) missing.push_back("rayQuery");
  // The compute shaders reduce statistics and list sizes across a subgroup (basic, arithmetic)
  // and branch on subgroup votes; without them pipeline creation fails later with no reason given.
  VkPhysicalDeviceSubgroupProperties sg{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &sg};
  vkGetPhysicalDeviceProperties2(pd, &p2);
  if (!(sg.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT)) missing.push_back("compute subgroups");
  constexpr VkSubgroupFeatureFlags kOps = VK_SUBGROUP_FEATURE_BASIC_BIT |
                                          VK_SUBGROUP_FEATURE_ARITHMETIC_BIT |
                                          VK_SUBGROUP_FEATURE_VOTE_BIT;
  if ((sg.supportedOperations & kOps) != kOps)
    missing.push_back("subgroup basic, arithmetic and vote operations");
  return missing;
}

int typeRank(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 3;
    default:
      return 4;
  }
}

const char* typeName(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "CPU";
    default:
      return "other";
  }
}

uint64_t deviceLocalBytes(const VkPhysicalDeviceMemoryProperties& mp) {
  uint64_t most = 0;
  for (uint32_t i = 0; i < mp.memoryHeapCount; ++i)
    if (mp.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
      most = std::max<uint64_t>(most, mp.memoryHeaps[i].size);
  return most ? most : UINT64_MAX;
}

}  // namespace sm::vk
