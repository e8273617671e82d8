// What a physical device offers against what a Context needs: the extensions and features it
// enables, what a device lacks (reported per device when none is usable), and the order in which
// usable devices are preferred. Internal to the vk wrapper (context.cpp); no Vulkan object is
// created here.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vk/context.h"

namespace sm::vk {

std::vector<const char*> requiredDeviceExtensions(const ContextOptions& o);

// Feature chain we query and then enable, kept in one struct so pNext pointers stay valid.
struct FeatureChain {
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR as{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  VkPhysicalDeviceRayQueryFeaturesKHR rq{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  explicit FeatureChain(bool rayQuery) {
    f2.pNext = &v12;
    if (rayQuery) {
      v12.pNext = &as;
      as.pNext = &rq;
    }
  }
  FeatureChain(const FeatureChain&) = delete;
};

bool hasExtension(VkPhysicalDevice pd, const char* name);
// Everything `pd` lacks for `o`, in words for the device report; empty when it is usable.
std::vector<std::string> missingFor(VkPhysicalDevice pd, const ContextOptions& o);
// Preference among usable devices: discrete, integrated, virtual, CPU, other (lower first).
int typeRank(VkPhysicalDeviceType t);
const char* typeName(VkPhysicalDeviceType t);
// The largest device-local heap: what one rank's buffers can hold at most.
uint64_t deviceLocalBytes(const VkPhysicalDeviceMemoryProperties& mp);

}  // namespace sm::vk
