#include "vk/context.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "vk/device_support.h"
#include "vk/vk_error.h"

namespace sm::vk {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

// The layer's spec version, 0 when it is not installed.
uint32_t layerVersion(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  for (const VkLayerProperties& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return l.specVersion;
  return 0;
}

bool instanceExtensionAvailable(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> ext(n);
  vkEnumerateInstanceExtensionProperties(nullptr, &n, ext.data());
  return std::any_of(ext.begin(), ext.end(),
                     [&](auto& e) { return std::strcmp(e.extensionName, name) == 0; });
}

// "1048576", "64K", "512M", "2G".
uint64_t parseByteCount(const char* what, const char* text) {
  char* end = nullptr;
  errno = 0;
  unsigned long long v = std::strtoull(text, &end, 10);
  int shift = 0;
  static const char* units = "KkMmGg";
  if (end != text && *end && !end[1] && std::strchr(units, *end)) {
    shift = 10 * int(1 + (std::strchr(units, *end) - units) / 2);
    ++end;
  }
  if (end == text || *end || errno || *text == '-' || v > (UINT64_MAX >> shift))
    throw std::invalid_argument(std::string(what) + ": '" + text +
                                "' is not a byte count (e.g. 268435456, 256M, 2G)");
  return uint64_t(v) << shift;
}

// Keeps the Vulkan drivers loaded for the rest of the process. Why: NVIDIA's driver (580, on an
// H100) cannot be loaded again after the loader unloaded it, which the loader does when the last
// instance goes. A process that makes contexts one after another (in-process ranks, the in situ
// library's users, test suites) then found no driver from some point on: the loader logged
// "Could not get 'vkCreateInstance' via 'vk_icdGetInstanceProcAddr'". One plain instance held
// until exit keeps every driver loaded, as LD_PRELOAD of the driver did; a failure here is left to
// the caller's own vkCreateInstance to report.
void holdDriversLoaded() {
  struct Holder {
    VkInstance instance = VK_NULL_HANDLE;
    Holder() {
      VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
      app.pApplicationName = "shellmarch (drivers held)";
      app.apiVersion = VK_API_VERSION_1_2;
      VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
      ci.pApplicationInfo = &app;
      if (vkCreateInstance(&ci, nullptr, &instance) != VK_SUCCESS) instance = VK_NULL_HANDLE;
    }
    ~Holder() {
      if (instance) vkDestroyInstance(instance, nullptr);
    }
  };
  static Holder held;
}

// vkCreateInstance's result, in words where the raw code misleads: the loader answers
// VK_ERROR_INCOMPATIBLE_DRIVER when it found no driver it could load (or only ones older than the
// API version asked for), which reads like a version mismatch.
void checkInstanceCreated(VkResult made) {
  if (made == VK_ERROR_INCOMPATIBLE_DRIVER)
    throw VulkanError(
        "no Vulkan driver could be loaded, or none supports Vulkan 1.2 (vkCreateInstance: "
        "VK_ERROR_INCOMPATIBLE_DRIVER); install one (on Debian 12: mesa-vulkan-drivers from "
        "bookworm-backports, for lavapipe) or point VK_DRIVER_FILES at the driver's manifest; "
        "VK_LOADER_DEBUG=driver tells why",
        made);
  SM_VK(made);
}

VkInstance plainInstance() {
  holdDriversLoaded();
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "shellmarch";
  app.apiVersion = VK_API_VERSION_1_2;
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pApplicationInfo = &app;
  VkInstance inst = VK_NULL_HANDLE;
  checkInstanceCreated(vkCreateInstance(&ci, nullptr, &inst));
  return inst;
}

}  // namespace

bool envFlag(const char* name) {
  const char* v = std::getenv(name);
  return v && *v && std::strcmp(v, "0") != 0;
}

std::vector<DeviceReport> Context::listDevices(const ContextOptions& options) {
  const ContextOptions o = withHiddenFromEnvironment(options);
  VkInstance inst = plainInstance();
  uint32_t n = 0;
  vkEnumeratePhysicalDevices(inst, &n, nullptr);
  std::vector<VkPhysicalDevice> devs(n);
  vkEnumeratePhysicalDevices(inst, &n, devs.data());
  std::vector<DeviceReport> out;
  for (uint32_t i = 0; i < n; ++i) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(devs[i], &p);
    TracerSupport s = tracerSupport(devs[i], o);
    std::vector<std::string> tracers;
    if (s.query()) tracers.push_back(tracerName(Tracer::Query));
    if (s.pipeline()) tracers.push_back(tracerName(Tracer::Pipeline));
    out.push_back({i, p.deviceName, p.deviceType, missingFor(devs[i], o), tracers});
  }
  vkDestroyInstance(inst, nullptr);
  return out;
}

Context::Context(const ContextOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ContextOptions o = withHiddenFromEnvironment(options);
  o.validation = o.validation || envFlag("SHELLMARCH_VALIDATION");
  forceStaging_ = o.forceStaging || envFlag("SHELLMARCH_FORCE_STAGING");
  try {
    createInstance(o);
    pickDevice(o);
    createDevice(o);
  } catch (...) {
    release();
    throw;
  }
  creationMs_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

Context::~Context() {
  release();
}

void Context::release() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    store_.reset();
    if (pool_) vkDestroyCommandPool(device_, pool_, nullptr);
    vkDestroyDevice(device_, nullptr);
    device_ = VK_NULL_HANDLE;
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
    messenger_ = VK_NULL_HANDLE;
  }
  if (instance_) {
    vkDestroyInstance(instance_, nullptr);
    instance_ = VK_NULL_HANDLE;
  }
}

void Context::createInstance(const ContextOptions& o) {
  holdDriversLoaded();
  std::vector<const char*> layers, ext;
  for (const auto& e : o.instanceExtensions) ext.push_back(e.c_str());
  debugUtils_ = instanceExtensionAvailable(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (debugUtils_) ext.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  validation_ = o.validation;
  if (validation_) {
    validationLayerVersion_ = layerVersion(kValidationLayer);
    if (!validationLayerVersion_)
      throw VulkanError(std::string("validation requested but ") + kValidationLayer +
                            " is not installed (Debian: vulkan-validationlayers)",
                        VK_ERROR_LAYER_NOT_PRESENT);
    layers.push_back(kValidationLayer);
    ext.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
  }
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "shellmarch";
  app.pEngineName = "shellmarch";
  app.apiVersion = VK_API_VERSION_1_2;
  VkValidationFeatureEnableEXT enables[] = {
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;
  VkDebugUtilsMessengerCreateInfoEXT mci{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  mci.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                        VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  mci.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                    VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                    VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  mci.pfnUserCallback = &Context::onMessage;
  mci.pUserData = this;
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pApplicationInfo = &app;
  ci.enabledLayerCount = uint32_t(layers.size());
  ci.ppEnabledLayerNames = layers.data();
  ci.enabledExtensionCount = uint32_t(ext.size());
  ci.ppEnabledExtensionNames = ext.data();
  // Validation features go in the instance's pNext chain; the messenger there also catches
  // messages from vkCreateInstance itself.
  if (validation_) {
    features.pNext = &mci;
    ci.pNext = &features;
  }
  checkInstanceCreated(vkCreateInstance(&ci, nullptr, &instance_));
  if (validation_ && debugUtils_) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    if (create) SM_VK(create(instance_, &mci, nullptr, &messenger_));
  }
}

void Context::pickDevice(const ContextOptions& o) {
  uint32_t n = 0;
  vkEnumeratePhysicalDevices(instance_, &n, nullptr);
  std::vector<VkPhysicalDevice> devs(n);
  vkEnumeratePhysicalDevices(instance_, &n, devs.data());
  std::ostringstream report;
  int best = -1, bestRank = 99;
  bool byIndex = !o.device.empty() && std::all_of(o.device.begin(), o.device.end(), ::isdigit);
  for (uint32_t i = 0; i < n; ++i) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(devs[i], &p);
    auto missing = missingFor(devs[i], o);
    // One line, devices separated by "; " (errors are one line: docs/RELIABILITY.md).
    report << (i ? "; [" : ": [") << i << "] " << p.deviceName << " (" << typeName(p.deviceType)
           << ")";
    if (missing.empty()) {
      report << ": usable";
    } else {
      report << ": lacks";
      for (auto& m : missing) report << " " << m;
    }
    if (!o.device.empty()) {
      bool match = byIndex ? std::to_string(i) == o.device
                           : std::strstr(p.deviceName, o.device.c_str()) != nullptr;
      if (!match) continue;
    }
    if (missing.empty() && typeRank(p.deviceType) < bestRank) {
      best = int(i);
      bestRank = typeRank(p.deviceType);
    }
  }
  if (best < 0) {
    std::string what = o.device.empty() ? std::string("no Vulkan device has what shellmarch needs")
                                        : "device '" + o.device + "': no usable device matches";
    if (o.rayTracing && o.tracer != Tracer::Auto)
      what += std::string(" for the ") + tracerName(o.tracer) + " tracer";
    if (n == 0) what = "no Vulkan device found (install mesa-vulkan-drivers for lavapipe)";
    throw VulkanError(what + report.str(), VK_ERROR_FEATURE_NOT_PRESENT);
  }
  physical_ = devs[best];
  vkGetPhysicalDeviceProperties(physical_, &props_);
  vkGetPhysicalDeviceMemoryProperties(physical_, &memProps_);
  memoryLimit_ = deviceLocalBytes(memProps_);
  if (const char* cap = std::getenv("SHELLMARCH_DEVICE_MEMORY_LIMIT"); cap && *cap)
    memoryLimit_ = std::min(memoryLimit_, parseByteCount("SHELLMARCH_DEVICE_MEMORY_LIMIT", cap));
  VkPhysicalDeviceSubgroupProperties sub{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceAccelerationStructurePropertiesKHR as{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
  const bool hasAs = hasExtension(physical_, VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME);
  if (hasAs) sub.pNext = &as;
  // Vulkan 1.1 (the device has 1.2: buffer device addresses); maintenance4's only with its
  // extension, as the instance asks for 1.2.
  VkPhysicalDeviceMaintenance3Properties m3{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
  VkPhysicalDeviceMaintenance4PropertiesKHR m4{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_PROPERTIES_KHR};
  const bool hasM4 = hasExtension(physical_, VK_KHR_MAINTENANCE_4_EXTENSION_NAME);
  m4.pNext = &sub;
  m3.pNext = hasM4 ? static_cast<void*>(&m4) : static_cast<void*>(&sub);
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  p2.pNext = &m3;
  vkGetPhysicalDeviceProperties2(physical_, &p2);
  bufferLimits_.maxAllocationSize = m3.maxMemoryAllocationSize;
  if (hasM4) bufferLimits_.maxBufferSize = m4.maxBufferSize;
  subgroupSize_ = sub.subgroupSize;
  asPrimitiveLimit_ = hasAs ? as.maxPrimitiveCount : 0;
  if (const char* cap = std::getenv("SHELLMARCH_AS_PRIMITIVE_LIMIT"); cap && *cap)
    asPrimitiveLimit_ =
        std::min(asPrimitiveLimit_, parseByteCount("SHELLMARCH_AS_PRIMITIVE_LIMIT", cap));
}

void Context::createDevice(const ContextOptions& o) {
  uint32_t nq = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &nq, nullptr);
  std::vector<VkQueueFamilyProperties> qf(nq);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &nq, qf.data());
  int family = -1;
  for (uint32_t i = 0; i < nq && family < 0; ++i)
    if ((qf[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && (qf[i].queueFlags & VK_QUEUE_GRAPHICS_BIT))
      family = int(i);
  for (uint32_t i = 0; i < nq && family < 0; ++i)
    if (qf[i].queueFlags & VK_QUEUE_COMPUTE_BIT) family = int(i);
  if (family < 0)
    throw VulkanError("the device has no compute queue", VK_ERROR_FEATURE_NOT_PRESENT);
  queueFamily_ = uint32_t(family);

  // Every tracer the device offers is enabled, the chosen one being the default: a renderer may
  // take the other (tests compare the two on one scene).
  const TracerSupport support =
      o.rayTracing ? tracerSupport(physical_, o) : TracerSupport{{"-"}, {"-"}};
  tracer_ = chooseTracer(o, support);
  const bool query = support.query(), pipeline = support.pipeline();
  FeatureChain have(o.rayTracing, query, pipeline);
  vkGetPhysicalDeviceFeatures2(physical_, &have.f2);
  FeatureChain want(o.rayTracing, query, pipeline);
  want.f2.features.shaderInt64 = VK_TRUE;
  want.f2.features.shaderFloat64 = have.f2.features.shaderFloat64;
  float64_ = have.f2.features.shaderFloat64;
  want.v12.bufferDeviceAddress = VK_TRUE;
  want.v12.scalarBlockLayout = VK_TRUE;
  want.v12.hostQueryReset = have.v12.hostQueryReset;
  if (o.rayTracing) want.as.accelerationStructure = VK_TRUE;
  want.rq.rayQuery = rayQuery_ = query;
  want.rt.rayTracingPipeline = rayTracingPipeline_ = pipeline;
  if (pipeline) readRayTracingLimits(o);
  float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = queueFamily_;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  auto ext = deviceExtensions(o, support);
  const bool shaderObjects = useShaderObjects(physical_, o, validationLayerVersion_);
  VkPhysicalDeviceShaderObjectFeaturesEXT so{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_OBJECT_FEATURES_EXT};
  if (shaderObjects) {
    so.shaderObject = VK_TRUE;
    so.pNext = want.f2.pNext;
    want.f2.pNext = &so;
    ext.push_back(VK_EXT_SHADER_OBJECT_EXTENSION_NAME);
    ext.push_back(VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME);  // what the extension requires
  }
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = &want.f2;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  dci.enabledExtensionCount = uint32_t(ext.size());
  dci.ppEnabledExtensionNames = ext.data();
  SM_VK(vkCreateDevice(physical_, &dci, nullptr, &device_));
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);

  auto load = [&](auto& fn, const char* name) {
    fn =
        reinterpret_cast<std::remove_reference_t<decltype(fn)>>(vkGetDeviceProcAddr(device_, name));
  };
  if (pipeline) {
    load(fn_.createRayTracingPipelines, "vkCreateRayTracingPipelinesKHR");
    load(fn_.getRayTracingShaderGroupHandles, "vkGetRayTracingShaderGroupHandlesKHR");
    load(fn_.cmdTraceRays, "vkCmdTraceRaysKHR");
  }
  if (o.rayTracing) {
    load(fn_.createAccelerationStructure, "vkCreateAccelerationStructureKHR");
    load(fn_.destroyAccelerationStructure, "vkDestroyAccelerationStructureKHR");
    load(fn_.getAccelerationStructureBuildSizes, "vkGetAccelerationStructureBuildSizesKHR");
    load(fn_.cmdBuildAccelerationStructures, "vkCmdBuildAccelerationStructuresKHR");
    load(fn_.getAccelerationStructureDeviceAddress, "vkGetAccelerationStructureDeviceAddressKHR");
    load(fn_.cmdWriteAccelerationStructuresProperties,
         "vkCmdWriteAccelerationStructuresPropertiesKHR");
    load(fn_.cmdCopyAccelerationStructure, "vkCmdCopyAccelerationStructureKHR");
  }
  if (debugUtils_)
    fn_.setDebugUtilsObjectName = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
        vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));

  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = queueFamily_;
  SM_VK(vkCreateCommandPool(device_, &pci, nullptr, &pool_));
  store_ = std::make_unique<PipelineStore>(
      physical_, device_, o.cacheDir.empty() ? ShaderCache::defaultFolder() : o.cacheDir,
      shaderObjects);
}

void Context::readRayTracingLimits(const ContextOptions& o) {
  VkPhysicalDeviceRayTracingPipelinePropertiesKHR rt{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_PROPERTIES_KHR};
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &rt};
  vkGetPhysicalDeviceProperties2(physical_, &p2);
  rtLimits_.handleSize = rt.shaderGroupHandleSize;
  rtLimits_.handleAlignment = std::max(rt.shaderGroupHandleAlignment, 1u);
  rtLimits_.baseAlignment = std::max(rt.shaderGroupBaseAlignment, 1u);
  rtLimits_.maxRecursionDepth = rt.maxRayRecursionDepth;
  rtLimits_.maxInvocations = rt.maxRayDispatchInvocationCount;
  rtLimits_.raygenSubgroups = raygenSubgroups(physical_, o);
}

uint32_t Context::memoryType(uint32_t bits, VkMemoryPropertyFlags want,
                             VkMemoryPropertyFlags avoid) const {
  for (int pass = 0; pass < 2; ++pass) {
    for (uint32_t i = 0; i < memProps_.memoryTypeCount; ++i) {
      VkMemoryPropertyFlags f = memProps_.memoryTypes[i].propertyFlags;
      if (!(bits & (1u << i)) || (f & want) != want) continue;
      if (pass == 0 && (f & avoid)) continue;
      return i;
    }
  }
  throw VulkanError("no suitable memory type", VK_ERROR_FEATURE_NOT_PRESENT);
}

bool Context::reserveDeviceMemory(uint64_t bytes) const {
  uint64_t used = memoryInUse_.load();
  do {
    if (bytes > memoryLimit_ - std::min(used, memoryLimit_)) return false;
  } while (!memoryInUse_.compare_exchange_weak(used, used + bytes));
  return true;
}

void Context::releaseDeviceMemory(uint64_t bytes) const {
  memoryInUse_ -= bytes;
}

void Context::setName(VkObjectType type, uint64_t handle, const std::string& name) const {
  if (!fn_.setDebugUtilsObjectName || !handle) return;
  VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = name.c_str();
  fn_.setDebugUtilsObjectName(device_, &info);
}

void Context::submitAndWait(const std::function<void(VkCommandBuffer)>& record) const {
  // The pool and the queue are externally synchronised: recording and submitting hold the lock,
  // waiting does not, so that one thread's upload runs while another's frame is on the queue.
  std::unique_lock lock(submitMutex_);
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = pool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd;
  SM_VK(vkAllocateCommandBuffers(device_, &ai, &cmd));
  struct Free {  // frees under the lock, taking it again after the wait
    const Context& ctx;
    std::unique_lock<std::mutex>& lock;
    VkCommandBuffer cmd;
    ~Free() {
      if (!lock.owns_lock()) lock.lock();
      vkFreeCommandBuffers(ctx.device_, ctx.pool_, 1, &cmd);
    }
  } guard{*this, lock, cmd};
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  SM_VK(vkBeginCommandBuffer(cmd, &bi));
  record(cmd);
  SM_VK(vkEndCommandBuffer(cmd));
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence;
  SM_VK(vkCreateFence(device_, &fci, nullptr, &fence));
  DeviceHandle<VkFence> fenceGuard(device_, fence, vkDestroyFence);
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  SM_VK(vkQueueSubmit(queue_, 1, &si, fence));
  lock.unlock();
  SM_VK(vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX));
}

std::vector<std::string> Context::validationMessages() const {
  std::lock_guard lock(messagesMutex_);
  return messages_;
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                  VkDebugUtilsMessageTypeFlagsEXT,
                                                  const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                  void* user) {
  auto* self = static_cast<Context*>(user);
  bool error = severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  (error ? self->errors_ : self->warnings_)++;
  std::string msg = std::string(error ? "validation error: " : "validation warning: ") +
                    (data && data->pMessage ? data->pMessage : "");
  std::fprintf(stderr, "shellmarch: %s\n", msg.c_str());
  std::lock_guard lock(self->messagesMutex_);
  if (self->messages_.size() < 100) self->messages_.push_back(msg);
  return VK_FALSE;
}

}  // namespace sm::vk
