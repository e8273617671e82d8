// Presentation: a surface (a window's, or a headless one) and a swapchain whose images are filled
// by a buffer-to-image copy of host pixels. The viewer's image already exists on the host after
// deep compositing (rank 0 gathers it), so one copy per frame is all presentation needs: no
// graphics pipeline, no render pass.
//
// One frame in flight: present() waits for the previous frame's copy before reusing the staging
// buffer and the acquire semaphore, which keeps the synchronisation easy to check (validation runs
// with synchronization validation in the tests).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/handle.h"

namespace sm::vk {

// Instance extensions a headless surface needs (VK_EXT_headless_surface: no window system).
std::vector<std::string> headlessSurfaceExtensions();

// Owns a VkSurfaceKHR. Surfaces belong to the instance, not the device, so DeviceHandle does not
// fit; the Surface must be destroyed before the Context that made its instance.
class Surface {
 public:
  Surface() = default;
  // Adopts a surface made on ctx's instance (e.g. by glfwCreateWindowSurface).
  Surface(const Context& ctx, VkSurfaceKHR surface);
  // A surface with no window behind it; the Context's instance must have enabled
  // headlessSurfaceExtensions().
  static Surface headless(const Context& ctx);
  Surface(Surface&& o) noexcept { *this = std::move(o); }
  Surface& operator=(Surface&& o) noexcept;
  ~Surface() { reset(); }

  VkSurfaceKHR handle() const { return surface_; }
  explicit operator bool() const { return surface_ != VK_NULL_HANDLE; }

 private:
  void reset();
  VkInstance instance_ = VK_NULL_HANDLE;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
};

// What present() did. OutOfDate: the swapchain no longer matches the surface (a resize); the frame
// may or may not have been shown: call recreate() and present it again.
enum class PresentResult { Presented, OutOfDate };

// An 8-bit RGBA image on the host, row 0 at the top.
struct HostImage {
  std::span<const uint8_t> rgba;
  uint32_t width = 0, height = 0;
};

class Swapchain {
 public:
  // `wanted` is used where the surface leaves the extent to the application (headless, Wayland);
  // a window surface dictates its own. Needs a Context created with swapchain = true.
  Swapchain(const Context& ctx, const Surface& surface, VkExtent2D wanted);
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  VkExtent2D extent() const { return extent_; }
  VkFormat format() const { return format_; }
  uint32_t imageCount() const { return uint32_t(images_.size()); }
  uint64_t recreations() const { return recreations_; }

  // Copies `image` to the top-left of the next swapchain image (the rest is filled with `fill`,
  // RGBA8) and queues it for presentation.
  PresentResult present(const HostImage& image, const uint8_t fill[4]);
  // Builds a new swapchain for the surface's current extent (waits for the device to be idle).
  void recreate(VkExtent2D wanted);

 private:
  void create(VkExtent2D wanted);
  void destroyImages();
  void fillStaging(const HostImage& image, const uint8_t fill[4]);
  void record(VkCommandBuffer cmd, uint32_t index) const;
  void submit(uint32_t index);

  const Context& ctx_;
  VkSurfaceKHR surface_;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  bool bgra_ = false;
  VkExtent2D extent_{0, 0};
  std::vector<VkImage> images_;
  // Signalled when an image's copy is done; one per image, because a presentation may still wait
  // on it until the presentation engine hands that image back.
  std::vector<DeviceHandle<VkSemaphore>> copied_;
  DeviceHandle<VkSemaphore> acquired_;
  DeviceHandle<VkFence> frameDone_;
  DeviceHandle<VkCommandPool> pool_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  Buffer staging_;
  bool submitted_ = false;
  uint64_t recreations_ = 0;
};

}  // namespace sm::vk
