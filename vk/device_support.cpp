#include "vk/device_support.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace sm::vk {

namespace {

constexpr VkSubgroupFeatureFlags kSubgroupOps = VK_SUBGROUP_FEATURE_BASIC_BIT |
                                                VK_SUBGROUP_FEATURE_ARITHMETIC_BIT |
                                                VK_SUBGROUP_FEATURE_VOTE_BIT;

VkPhysicalDeviceSubgroupProperties subgroupProperties(VkPhysicalDevice pd) {
  VkPhysicalDeviceSubgroupProperties sg{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &sg};
  vkGetPhysicalDeviceProperties2(pd, &p2);
  return sg;
}

// What the device lacks of `extension` and its `feature` (read through `chain`), or that the
// options hide it.
std::vector<std::string> lacks(VkPhysicalDevice pd, const char* extension, bool hidden,
                               bool (*feature)(const FeatureChain&), bool rayQuery) {
  if (hidden) return {std::string(extension) + " (hidden)"};
  if (!hasExtension(pd, extension)) return {extension};
  FeatureChain fc(true, rayQuery, !rayQuery);
  vkGetPhysicalDeviceFeatures2(pd, &fc.f2);
  if (!fc.as.accelerationStructure) return {"accelerationStructure"};
  if (!feature(fc)) return {rayQuery ? "rayQuery" : "rayTracingPipeline"};
  return {};
}

}  // namespace

TracerSupport tracerSupport(VkPhysicalDevice pd, const ContextOptions& o) {
  TracerSupport s;
  for (const char* e : {VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
                        VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME})
    if (!hasExtension(pd, e)) {
      s.queryLacks.push_back(e);
      s.pipelineLacks.push_back(e);
    }
  if (!s.queryLacks.empty()) return s;
  s.queryLacks = lacks(
      pd, VK_KHR_RAY_QUERY_EXTENSION_NAME, o.hide & kHideRayQuery,
      [](const FeatureChain& f) { return bool(f.rq.rayQuery); }, true);
  s.pipelineLacks = lacks(
      pd, VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME, o.hide & kHideRayTracingPipeline,
      [](const FeatureChain& f) { return bool(f.rt.rayTracingPipeline); }, false);
  return s;
}

Tracer chooseTracer(const ContextOptions& o, const TracerSupport& s) {
  if (!o.rayTracing) return Tracer::Auto;
  switch (o.tracer) {
    case Tracer::Query:
      return s.query() ? Tracer::Query : Tracer::Auto;
    case Tracer::Pipeline:
      return s.pipeline() ? Tracer::Pipeline : Tracer::Auto;
    case Tracer::Auto:
      break;
  }
  return s.query() ? Tracer::Query : s.pipeline() ? Tracer::Pipeline : Tracer::Auto;
}

std::vector<const char*> deviceExtensions(const ContextOptions& o, const TracerSupport& s) {
  std::vector<const char*> ext;
  if (o.rayTracing) {
    ext.push_back(VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME);
    ext.push_back(VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME);
    if (s.query()) ext.push_back(VK_KHR_RAY_QUERY_EXTENSION_NAME);
    if (s.pipeline()) ext.push_back(VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME);
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
  if (o.swapchain && !hasExtension(pd, VK_KHR_SWAPCHAIN_EXTENSION_NAME))
    missing.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  if (!missing.empty()) return missing;
  if (o.rayTracing) {
    // Per tracer, what is missing for it: the one asked for, or for auto both (either would do).
    TracerSupport s = tracerSupport(pd, o);
    auto add = [&](const char* what, const std::vector<std::string>& lack) {
      std::string m = what;
      for (size_t i = 0; i < lack.size(); ++i) m += (i ? ", " : " (") + lack[i];
      missing.push_back(m + ")");
    };
    const bool wantQuery = o.tracer != Tracer::Pipeline, wantPipeline = o.tracer != Tracer::Query;
    if (wantQuery && !s.query() && (o.tracer == Tracer::Query || !s.pipeline()))
      add("ray queries", s.queryLacks);
    if (wantPipeline && !s.pipeline() && (o.tracer == Tracer::Pipeline || !s.query()))
      add(o.tracer == Tracer::Auto ? "and a ray tracing pipeline" : "a ray tracing pipeline",
          s.pipelineLacks);
  }
  FeatureChain fc(false, false, false);
  vkGetPhysicalDeviceFeatures2(pd, &fc.f2);
  if (!fc.v12.bufferDeviceAddress) missing.push_back("bufferDeviceAddress");
  if (!fc.v12.scalarBlockLayout) missing.push_back("scalarBlockLayout");
  if (!fc.f2.features.shaderInt64) missing.push_back("shaderInt64");
  // The compute shaders reduce statistics and list sizes across a subgroup (basic, arithmetic)
  // and branch on subgroup votes; without them pipeline creation fails later with no reason given.
  VkPhysicalDeviceSubgroupProperties sg = subgroupProperties(pd);
  if (!(sg.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT)) missing.push_back("compute subgroups");
  if ((sg.supportedOperations & kSubgroupOps) != kSubgroupOps)
    missing.push_back("subgroup basic, arithmetic and vote operations");
  return missing;
}

bool useShaderObjects(VkPhysicalDevice pd, const ContextOptions& o, uint32_t validationLayer) {
  VkPhysicalDeviceProperties p;
  vkGetPhysicalDeviceProperties(pd, &p);
  if ((o.hide & kHideShaderObject) || p.deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU) return false;
  // Layers older than the extension (Debian 12's 1.3.239) reject its structures and report every
  // dispatch of a shader object as one without a pipeline.
  if (validationLayer && validationLayer < VK_MAKE_API_VERSION(0, 1, 3, 246)) return false;
  if (!hasExtension(pd, VK_EXT_SHADER_OBJECT_EXTENSION_NAME) ||
      !hasExtension(pd, VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME))
    return false;
  VkPhysicalDeviceShaderObjectFeaturesEXT so{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_OBJECT_FEATURES_EXT};
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &so};
  vkGetPhysicalDeviceFeatures2(pd, &f2);
  return so.shaderObject;
}

bool raygenSubgroups(VkPhysicalDevice pd, const ContextOptions& o) {
  VkPhysicalDeviceSubgroupProperties sg = subgroupProperties(pd);
  return !(o.hide & kHideRaygenSubgroups) &&
         (sg.supportedStages & VK_SHADER_STAGE_RAYGEN_BIT_KHR) &&
         (sg.supportedOperations & kSubgroupOps) == kSubgroupOps;
}

ContextOptions withHiddenFromEnvironment(ContextOptions o) {
  const char* env = std::getenv("SHELLMARCH_HIDE");
  if (!env || !*env) return o;
  std::string list = env;
  size_t at = 0;
  while (at <= list.size()) {
    size_t end = std::min(list.find(',', at), list.size());
    std::string name = list.substr(at, end - at);
    if (name == "ray_query")
      o.hide |= kHideRayQuery;
    else if (name == "ray_tracing_pipeline")
      o.hide |= kHideRayTracingPipeline;
    else if (name == "raygen_subgroups")
      o.hide |= kHideRaygenSubgroups;
    else if (name == "shader_object")
      o.hide |= kHideShaderObject;
    else if (!name.empty())
      throw std::invalid_argument("SHELLMARCH_HIDE: '" + name +
                                  "' is not ray_query, ray_tracing_pipeline, raygen_subgroups or "
                                  "shader_object");
    at = end + 1;
  }
  return o;
}

const char* tracerName(Tracer t) {
  switch (t) {
    case Tracer::Query:
      return "query";
    case Tracer::Pipeline:
      return "pipeline";
    case Tracer::Auto:
      break;
  }
  return "auto";
}

Tracer parseTracer(const std::string& what, const std::string& text) {
  for (Tracer t : {Tracer::Auto, Tracer::Query, Tracer::Pipeline})
    if (text == tracerName(t)) return t;
  throw std::invalid_argument(what + ": '" + text + "' is not auto, query or pipeline");
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
