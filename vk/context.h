// Vulkan instance, device and queue: the one object every GPU module receives.
//
// Device choice: devices that have every required extension and feature are ranked discrete,
// integrated, virtual, CPU (lavapipe); ContextOptions::device overrides with an index or a name
// substring. When none qualifies the error lists every device and what it lacks.
// Validation: with ContextOptions::validation (or SHELLMARCH_VALIDATION=1) the Khronos layer runs
// with synchronization validation; every message is printed and counted, and tests fail on them.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/handle.h"
#include "vk/pipeline_store.h"

namespace sm::vk {

// How shell crossings are traced (docs/ARCHITECTURE.md, "Tracers"): ray queries from compute
// shaders, or a ray tracing pipeline (ray generation, intersection and any-hit shaders) where the
// device offers only that (NVIDIA's GPUs without RT cores). Auto takes ray queries where offered.
enum class Tracer { Auto, Query, Pipeline };
const char* tracerName(Tracer t);  // "auto", "query", "pipeline"
// Throws std::invalid_argument naming `what` (an option) for anything but those three.
Tracer parseTracer(const std::string& what, const std::string& text);

// Capabilities a context treats as absent although the device has them (ContextOptions::hide, or
// SHELLMARCH_HIDE=ray_query,ray_tracing_pipeline,raygen_subgroups,shader_object): tests of the
// choices made on devices that lack them.
enum HideBits : uint32_t {
  kHideRayQuery = 1,
  kHideRayTracingPipeline = 2,
  kHideRaygenSubgroups = 4,
  kHideShaderObject = 8,
};

struct ContextOptions {
  bool validation = false;  // also forced on by SHELLMARCH_VALIDATION=1
  bool rayTracing = true;   // acceleration structures and a tracer (renderer); not needed by the
                            // compositor alone
  Tracer tracer = Tracer::Auto;
  uint32_t hide = 0;   // HideBits, or'ed with SHELLMARCH_HIDE's
  std::string device;  // "" = best, "N" = index N, else a substring of the name
  std::vector<std::string> instanceExtensions;  // e.g. what GLFW needs for a window
  bool swapchain = false;                       // enable VK_KHR_swapchain
  bool forceStaging = false;                    // never map device buffers: exercise staging copies
  // Where compiled shaders are kept between processes (pipeline_store.h): "" for
  // ShaderCache::defaultFolder(), "none" for nowhere.
  std::string cacheDir;
};

// Extension entry points, loaded with vkGetDeviceProcAddr.
struct DeviceFunctions {
  PFN_vkCreateAccelerationStructureKHR createAccelerationStructure = nullptr;
  PFN_vkDestroyAccelerationStructureKHR destroyAccelerationStructure = nullptr;
  PFN_vkGetAccelerationStructureBuildSizesKHR getAccelerationStructureBuildSizes = nullptr;
  PFN_vkCmdBuildAccelerationStructuresKHR cmdBuildAccelerationStructures = nullptr;
  PFN_vkGetAccelerationStructureDeviceAddressKHR getAccelerationStructureDeviceAddress = nullptr;
  PFN_vkCmdWriteAccelerationStructuresPropertiesKHR cmdWriteAccelerationStructuresProperties =
      nullptr;
  PFN_vkCmdCopyAccelerationStructureKHR cmdCopyAccelerationStructure = nullptr;
  PFN_vkCreateRayTracingPipelinesKHR createRayTracingPipelines = nullptr;
  PFN_vkGetRayTracingShaderGroupHandlesKHR getRayTracingShaderGroupHandles = nullptr;
  PFN_vkCmdTraceRaysKHR cmdTraceRays = nullptr;
  PFN_vkSetDebugUtilsObjectNameEXT setDebugUtilsObjectName = nullptr;
};

// What the shader binding table and trace calls of a ray tracing pipeline must respect.
struct RayTracingLimits {
  uint32_t handleSize = 0, handleAlignment = 1, baseAlignment = 1;
  uint32_t maxRecursionDepth = 0;
  uint32_t maxInvocations = 0;   // per vkCmdTraceRaysKHR
  bool raygenSubgroups = false;  // subgroup basic, vote and arithmetic in ray generation shaders
};

// The device's limits on one buffer: its size (maxBufferSize of
// VkPhysicalDeviceMaintenance4Properties, where the device has VK_KHR_maintenance4) and its memory
// (maxMemoryAllocationSize of VkPhysicalDeviceMaintenance3Properties). UINT64_MAX where the device
// does not say.
struct BufferLimits {
  uint64_t maxBufferSize = UINT64_MAX;
  uint64_t maxAllocationSize = UINT64_MAX;
};

struct DeviceReport {
  uint32_t index;
  std::string name;
  VkPhysicalDeviceType type;
  std::vector<std::string> missing;  // empty = usable
  std::vector<std::string> tracers;  // the tracers it offers ("query", "pipeline")
};

class Context {
 public:
  explicit Context(const ContextOptions& options = {});
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physical_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queueFamily() const { return queueFamily_; }
  const DeviceFunctions& fn() const { return fn_; }
  const VkPhysicalDeviceProperties& properties() const { return props_; }
  std::string deviceName() const { return props_.deviceName; }
  bool isCpu() const { return props_.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU; }
  bool hasFloat64() const { return float64_; }
  // The tracers enabled: every one the device offers and the options do not hide.
  bool hasRayQuery() const { return rayQuery_; }
  bool hasRayTracingPipeline() const { return rayTracingPipeline_; }
  // The tracer renderers of this context use: ContextOptions::tracer, or for Auto ray queries
  // where the device offers them, else the pipeline. Auto without rayTracing: Auto.
  Tracer tracer() const { return tracer_; }
  const RayTracingLimits& rayTracingLimits() const { return rtLimits_; }
  bool forceStaging() const { return forceStaging_; }
  uint32_t subgroupSize() const { return subgroupSize_; }
  // The most primitives one bottom-level acceleration structure may hold (maxPrimitiveCount; 0
  // without acceleration structures), or SHELLMARCH_AS_PRIMITIVE_LIMIT where smaller: the test
  // hook, as no test can build a shell at the spec's minimum of 2^29 - 1.
  uint64_t asPrimitiveLimit() const { return asPrimitiveLimit_; }
  // What one buffer may hold (vk::Buffer refuses larger ones before allocating).
  const BufferLimits& bufferLimits() const { return bufferLimits_; }
  double timestampPeriodNs() const { return props_.limits.timestampPeriod; }
  // How pipelines are compiled and kept, and what each cost (the startup statistics).
  const PipelineStore& pipelines() const { return *store_; }
  // Milliseconds the constructor took: instance, device and the pipeline cache's loading.
  double creationMs() const { return creationMs_; }

  uint32_t memoryType(uint32_t typeBits, VkMemoryPropertyFlags want,
                      VkMemoryPropertyFlags avoid = 0) const;

  // Device memory this context may hold at once: the largest device-local heap, or less where
  // SHELLMARCH_DEVICE_MEMORY_LIMIT (bytes, or with a K, M or G suffix) says so. The variable lets
  // tests run a renderer out of memory on any device; out-of-memory messages compare what a
  // rank needs with this.
  uint64_t deviceMemoryLimit() const { return memoryLimit_; }
  uint64_t deviceMemoryInUse() const { return memoryInUse_; }
  // Buffer's bookkeeping: false (nothing reserved) when `bytes` more would pass the limit.
  bool reserveDeviceMemory(uint64_t bytes) const;
  void releaseDeviceMemory(uint64_t bytes) const;
  void setName(VkObjectType type, uint64_t handle, const std::string& name) const;

  // Records commands into a one-time command buffer, submits and waits. Thread-safe: threads
  // record and submit one at a time and wait for their own work side by side (`record` must not
  // call submitAndWait).
  void submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;
  // The queue is externally synchronised, and submitAndWait may run on another thread (a step
  // read ahead uploads there): hold this around any other use of queue(), and around
  // vkDeviceWaitIdle. Not while calling submitAndWait.
  std::unique_lock<std::mutex> lockQueue() const { return std::unique_lock(submitMutex_); }

  // Validation messages seen so far (errors and warnings), for tests.
  uint64_t validationErrors() const { return errors_; }
  uint64_t validationWarnings() const { return warnings_; }
  std::vector<std::string> validationMessages() const;
  bool validationEnabled() const { return validation_; }

  // Every physical device and what it lacks for these options.
  static std::vector<DeviceReport> listDevices(const ContextOptions& options);

 private:
  void release();
  void createInstance(const ContextOptions& o);
  void pickDevice(const ContextOptions& o);
  void createDevice(const ContextOptions& o);
  void readRayTracingLimits(const ContextOptions& o);
  static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                  VkDebugUtilsMessageTypeFlagsEXT types,
                                                  const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                  void* user);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties props_{};
  VkPhysicalDeviceMemoryProperties memProps_{};
  DeviceFunctions fn_;
  bool validation_ = false, debugUtils_ = false, float64_ = false, rayQuery_ = false;
  bool rayTracingPipeline_ = false;
  Tracer tracer_ = Tracer::Auto;
  RayTracingLimits rtLimits_;
  bool forceStaging_ = false;
  uint32_t subgroupSize_ = 1;
  uint64_t asPrimitiveLimit_ = 0;
  BufferLimits bufferLimits_;
  uint64_t memoryLimit_ = UINT64_MAX;
  uint32_t validationLayerVersion_ = 0;
  std::unique_ptr<PipelineStore> store_;
  double creationMs_ = 0;
  mutable std::atomic<uint64_t> memoryInUse_{0};
  std::atomic<uint64_t> errors_{0}, warnings_{0};
  mutable std::mutex messagesMutex_;
  mutable std::mutex submitMutex_;  // command pool and queue
  std::vector<std::string> messages_;
};

// True when the environment variable is set to a non-empty value other than "0".
bool envFlag(const char* name);

}  // namespace sm::vk
