// Move-only owner of one Vulkan device object; destroys it with the function it was given.
#pragma once

#include <utility>

#include <vulkan/vulkan.h>

namespace sm::vk {

template <typename T>
class DeviceHandle {
 public:
  using DestroyFn = void (*)(VkDevice, T, const VkAllocationCallbacks*);
  DeviceHandle() = default;
  DeviceHandle(VkDevice device, T handle, DestroyFn destroy)
      : device_(device), handle_(handle), destroy_(destroy) {}
  ~DeviceHandle() { reset(); }
  DeviceHandle(const DeviceHandle&) = delete;
  DeviceHandle& operator=(const DeviceHandle&) = delete;
  DeviceHandle(DeviceHandle&& o) noexcept { *this = std::move(o); }
  DeviceHandle& operator=(DeviceHandle&& o) noexcept {
    if (this != &o) {
      reset();
      device_ = std::exchange(o.device_, VK_NULL_HANDLE);
      handle_ = std::exchange(o.handle_, T(VK_NULL_HANDLE));
      destroy_ = std::exchange(o.destroy_, nullptr);
    }
    return *this;
  }
  void reset() {
    if (handle_ != T(VK_NULL_HANDLE) && destroy_) destroy_(device_, handle_, nullptr);
    handle_ = T(VK_NULL_HANDLE);
  }
  T get() const { return handle_; }
  explicit operator bool() const { return handle_ != T(VK_NULL_HANDLE); }

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  T handle_ = T(VK_NULL_HANDLE);
  DestroyFn destroy_ = nullptr;
};

}  // namespace sm::vk
