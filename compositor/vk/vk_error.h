// Errors from the Vulkan layer. VulkanError carries the failing call and VkResult; running out of
// device memory is its own type so that callers can say what would fit instead.
#pragma once

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
  using VulkanError::VulkanError;
};

[[noreturn]] void throwVkError(const char* expr, VkResult r, const char* file, int line);

}  // namespace sm::vk

#define SM_VK(expr)                                                                          \
  do {                                                                                       \
    VkResult sm_vk_r_ = (expr);                                                              \
    if (sm_vk_r_ != VK_SUCCESS) ::sm::vk::throwVkError(#expr, sm_vk_r_, __FILE__, __LINE__); \
  } while (0)
