// What a physical device offers against what a Context needs: the extensions and features it
// enables, what a device lacks (reported per device when none is usable), and the order in which
// usable devices are preferred. Internal to the vk wrapper (context.cpp); no Vulkan object is
// created here.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vk/context.h"
#include "vk/shader_object_ext.h"

namespace sm::vk {

// What a device lacks for each tracer, given the options' hide mask; empty where it offers it.
struct TracerSupport {
  std::vector<std::string> queryLacks, pipelineLacks;
  bool query() const { return queryLacks.empty(); }
  bool pipeline() const { return pipelineLacks.empty(); }
};
TracerSupport tracerSupport(VkPhysicalDevice pd, const ContextOptions& o);
// The tracer a context of `o` uses where `s` is offered; Auto when o needs none or none fits.
Tracer chooseTracer(const ContextOptions& o, const TracerSupport& s);

// The extensions a context of `o` enables: those of every tracer in `s` it offers.
std::vector<const char*> deviceExtensions(const ContextOptions& o, const TracerSupport& s);

// Feature chain we query and then enable, kept in one struct so pNext pointers stay valid. Only the
// structures of extensions the device has are chained.
struct FeatureChain {
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR as{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  VkPhysicalDeviceRayQueryFeaturesKHR rq{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  VkPhysicalDeviceRayTracingPipelineFeaturesKHR rt{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
  FeatureChain(bool accelerationStructure, bool rayQuery, bool rayTracingPipeline) {
    void** next = &f2.pNext;
    auto link = [&](auto& s) {
      *next = &s;
      next = &s.pNext;
    };
    link(v12);
    if (accelerationStructure) link(as);
    if (rayQuery) link(rq);
    if (rayTracingPipeline) link(rt);
  }
  FeatureChain(const FeatureChain&) = delete;
};

bool hasExtension(VkPhysicalDevice pd, const char* name);
// Everything `pd` lacks for `o`, in words for the device report; empty when it is usable.
std::vector<std::string> missingFor(VkPhysicalDevice pd, const ContextOptions& o);
// Whether compute shaders are made as shader objects, so that their binaries can be stored
// (pipeline_store.h): on CPU devices that offer VK_EXT_shader_object, unless hidden or validated
// by a layer (`validationLayer`: its spec version, 0 for none) too old to know the extension.
bool useShaderObjects(VkPhysicalDevice pd, const ContextOptions& o, uint32_t validationLayer);
// Whether ray generation shaders may use subgroup basic, vote and arithmetic operations.
bool raygenSubgroups(VkPhysicalDevice pd, const ContextOptions& o);
// Preference among usable devices: discrete, integrated, virtual, CPU, other (lower first).
int typeRank(VkPhysicalDeviceType t);
const char* typeName(VkPhysicalDeviceType t);
// The largest device-local heap: what one rank's buffers can hold at most.
uint64_t deviceLocalBytes(const VkPhysicalDeviceMemoryProperties& mp);
// The options with SHELLMARCH_HIDE's capabilities added to o.hide; throws std::invalid_argument
// for a name it does not know.
ContextOptions withHiddenFromEnvironment(ContextOptions o);

}  // namespace sm::vk
