// Errors from the Vulkan layer. VulkanError carries the failing call and VkResult; running out of
// device memory is its own type so that callers can say what would fit instead.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include <vulkan/vulkan.h>

namespace sm::vk {

const char* resultName(VkResult r);

class VulkanError : public std::runtime_error {
 public:
  VulkanError(const std::string& what, VkResult r) : std::runtime_error(what), result_(r) {}
  VkResult result() const { return result_; }

 private:
  VkResult result_;
};

class DeviceMemoryError : public VulkanError {
 public:
  DeviceMemoryError(const std::string& what, VkResult r, uint64_t requested = 0, uint64_t inUse = 0)
      : VulkanError(what, r), requested_(requested), inUse_(inUse) {}
  // Bytes of the allocation that failed, and the bytes the context held then (0 when a driver
  // call other than an allocation reported it): callers that unwind past the buffers still know.
  uint64_t requested() const { return requested_; }
  uint64_t inUse() const { return inUse_; }

 private:
  uint64_t requested_, inUse_;
};

// A buffer larger than the device takes in one buffer or one allocation (vk::BufferLimits),
// refused before anything is created: a DeviceMemoryError, so that callers that fall back on less
// memory, or say what would fit, treat it as such.
class BufferLimitError : public DeviceMemoryError {
 public:
  using DeviceMemoryError::DeviceMemoryError;
};

[[noreturn]] void throwVkError(const char* expr, VkResult r, const char* file, int line);

}  // namespace sm::vk

#define SM_VK(expr)                                                                          \
  do {                                                                                       \
    VkResult sm_vk_r_ = (expr);                                                              \
    if (sm_vk_r_ != VK_SUCCESS) ::sm::vk::throwVkError(#expr, sm_vk_r_, __FILE__, __LINE__); \
  } while (0)
