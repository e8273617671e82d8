#include "vk/present/swapchain.h"

#include <algorithm>
#include <cstring>

#include "vk/vk_error.h"

namespace sm::vk {
namespace {

// UNORM first: the host pixels are already display-encoded bytes (as in a PNG), and a copy does
// not convert, so an SRGB image would show the same bytes anyway; only the channel order matters.
constexpr VkFormat kFormats[] = {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM,
                                 VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB};

VkSurfaceFormatKHR pickFormat(VkPhysicalDevice pd, VkSurfaceKHR surface) {
  uint32_t n = 0;
  SM_VK(vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface, &n, nullptr));
  std::vector<VkSurfaceFormatKHR> formats(n);
  SM_VK(vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface, &n, formats.data()));
  for (VkFormat want : kFormats)
    for (const auto& f : formats)
      if (f.format == want && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return f;
  throw VulkanError("the surface offers no 8-bit RGBA or BGRA format",
                    VK_ERROR_FORMAT_NOT_SUPPORTED);
}

VkCompositeAlphaFlagBitsKHR pickAlpha(VkCompositeAlphaFlagsKHR supported) {
  if (supported & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR) return VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  for (uint32_t bit = 1; bit; bit <<= 1)
    if (supported & bit) return VkCompositeAlphaFlagBitsKHR(bit);
  return VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
}

VkExtent2D pickExtent(const VkSurfaceCapabilitiesKHR& caps, VkExtent2D wanted) {
  if (caps.currentExtent.width != UINT32_MAX) return caps.currentExtent;
  return {std::clamp(wanted.width, caps.minImageExtent.width, caps.maxImageExtent.width),
          std::clamp(wanted.height, caps.minImageExtent.height, caps.maxImageExtent.height)};
}

DeviceHandle<VkSemaphore> makeSemaphore(const Context& ctx, const std::string& name) {
  VkSemaphoreCreateInfo ci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VkSemaphore s;
  SM_VK(vkCreateSemaphore(ctx.device(), &ci, nullptr, &s));
  ctx.setName(VK_OBJECT_TYPE_SEMAPHORE, uint64_t(s), name);
  return DeviceHandle<VkSemaphore>(ctx.device(), s, vkDestroySemaphore);
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags srcStage, VkAccessFlags srcAccess,
                  VkPipelineStageFlags dstStage, VkAccessFlags dstAccess) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = srcAccess;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

}  // namespace

std::vector<std::string> headlessSurfaceExtensions() {
  return {VK_KHR_SURFACE_EXTENSION_NAME, VK_EXT_HEADLESS_SURFACE_EXTENSION_NAME};
}

Surface::Surface(const Context& ctx, VkSurfaceKHR surface)
    : instance_(ctx.instance()), surface_(surface) {}

Surface Surface::headless(const Context& ctx) {
  // An extension entry point: the loader does not export it.
  auto create = reinterpret_cast<PFN_vkCreateHeadlessSurfaceEXT>(
      vkGetInstanceProcAddr(ctx.instance(), "vkCreateHeadlessSurfaceEXT"));
  if (!create)
    throw VulkanError("VK_EXT_headless_surface is not enabled on this instance",
                      VK_ERROR_EXTENSION_NOT_PRESENT);
  VkHeadlessSurfaceCreateInfoEXT ci{VK_STRUCTURE_TYPE_HEADLESS_SURFACE_CREATE_INFO_EXT};
  VkSurfaceKHR s;
  SM_VK(create(ctx.instance(), &ci, nullptr, &s));
  return Surface(ctx, s);
}

Surface& Surface::operator=(Surface&& o) noexcept {
  if (this != &o) {
    reset();
    instance_ = std::exchange(o.instance_, VK_NULL_HANDLE);
    surface_ = std::exchange(o.surface_, VK_NULL_HANDLE);
  }
  return *this;
}

void Surface::reset() {
  if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
  surface_ = VK_NULL_HANDLE;
}

Swapchain::Swapchain(const Context& ctx, const Surface& surface, VkExtent2D wanted)
    : ctx_(ctx), surface_(surface.handle()) {
  VkBool32 supported = VK_FALSE;
  SM_VK(vkGetPhysicalDeviceSurfaceSupportKHR(ctx.physicalDevice(), ctx.queueFamily(), surface_,
                                             &supported));
  if (!supported)
    throw VulkanError(ctx.deviceName() + ": its queue cannot present to this surface",
                      VK_ERROR_FEATURE_NOT_PRESENT);
  VkDevice dev = ctx.device();
  acquired_ = makeSemaphore(ctx, "swapchain acquired");
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence;
  SM_VK(vkCreateFence(dev, &fci, nullptr, &fence));
  frameDone_ = DeviceHandle<VkFence>(dev, fence, vkDestroyFence);
  ctx.setName(VK_OBJECT_TYPE_FENCE, uint64_t(fence), "swapchain frame done");
  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = ctx.queueFamily();
  VkCommandPool pool;
  SM_VK(vkCreateCommandPool(dev, &pci, nullptr, &pool));
  pool_ = DeviceHandle<VkCommandPool>(dev, pool, vkDestroyCommandPool);
  ctx.setName(VK_OBJECT_TYPE_COMMAND_POOL, uint64_t(pool), "swapchain commands");
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = pool;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  SM_VK(vkAllocateCommandBuffers(dev, &ai, &cmd_));
  ctx.setName(VK_OBJECT_TYPE_COMMAND_BUFFER, uint64_t(cmd_), "swapchain copy");
  create(wanted);
}

Swapchain::~Swapchain() {
  {
    auto queue = ctx_.lockQueue();
    vkDeviceWaitIdle(ctx_.device());
  }
  destroyImages();
  if (swapchain_) vkDestroySwapchainKHR(ctx_.device(), swapchain_, nullptr);
}

void Swapchain::destroyImages() {
  copied_.clear();
  images_.clear();
}

void Swapchain::create(VkExtent2D wanted) {
  VkPhysicalDevice pd = ctx_.physicalDevice();
  VkSurfaceCapabilitiesKHR caps;
  SM_VK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd, surface_, &caps));
  if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
    throw VulkanError("the surface's images cannot be copied to (no TRANSFER_DST usage)",
                      VK_ERROR_FEATURE_NOT_PRESENT);
  VkSurfaceFormatKHR format = pickFormat(pd, surface_);
  VkSwapchainKHR old = swapchain_;
  swapchain_ = VK_NULL_HANDLE;
  extent_ = pickExtent(caps, wanted);
  if (extent_.width == 0 || extent_.height == 0) {  // minimised: nothing to present to
    if (old) vkDestroySwapchainKHR(ctx_.device(), old, nullptr);
    return;
  }
  VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  ci.surface = surface_;
  ci.minImageCount = caps.minImageCount + 1;
  if (caps.maxImageCount) ci.minImageCount = std::min(ci.minImageCount, caps.maxImageCount);
  ci.imageFormat = format.format;
  ci.imageColorSpace = format.colorSpace;
  ci.imageExtent = extent_;
  ci.imageArrayLayers = 1;
  ci.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = caps.currentTransform;
  ci.compositeAlpha = pickAlpha(caps.supportedCompositeAlpha);
  ci.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always available; no tearing
  ci.clipped = VK_TRUE;
  ci.oldSwapchain = old;
  VkResult r = vkCreateSwapchainKHR(ctx_.device(), &ci, nullptr, &swapchain_);
  if (old) vkDestroySwapchainKHR(ctx_.device(), old, nullptr);
  SM_VK(r);
  ctx_.setName(VK_OBJECT_TYPE_SWAPCHAIN_KHR, uint64_t(swapchain_), "swapchain");
  format_ = format.format;
  bgra_ = format_ == VK_FORMAT_B8G8R8A8_UNORM || format_ == VK_FORMAT_B8G8R8A8_SRGB;
  uint32_t n = 0;
  SM_VK(vkGetSwapchainImagesKHR(ctx_.device(), swapchain_, &n, nullptr));
  images_.resize(n);
  SM_VK(vkGetSwapchainImagesKHR(ctx_.device(), swapchain_, &n, images_.data()));
  for (uint32_t i = 0; i < n; ++i) {
    ctx_.setName(VK_OBJECT_TYPE_IMAGE, uint64_t(images_[i]),
                 "swapchain image " + std::to_string(i));
    copied_.push_back(makeSemaphore(ctx_, "swapchain copied " + std::to_string(i)));
  }
  const VkDeviceSize bytes = VkDeviceSize(extent_.width) * extent_.height * 4;
  if (!staging_.valid() || staging_.size() < bytes)
    staging_ = Buffer(ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Upload,
                      "swapchain staging");
}

void Swapchain::recreate(VkExtent2D wanted) {
  // Waiting for the queue also waits for the presentations that still hold our semaphores.
  {
    auto queue = ctx_.lockQueue();
    SM_VK(vkQueueWaitIdle(ctx_.queue()));
    SM_VK(vkDeviceWaitIdle(ctx_.device()));
  }
  destroyImages();
  create(wanted);
  ++recreations_;
}

void Swapchain::fillStaging(const HostImage& image, const uint8_t fill[4]) {
  auto* dst = static_cast<uint8_t*>(staging_.mapped());
  if (!dst) throw VulkanError("swapchain staging buffer is not mapped", VK_ERROR_MEMORY_MAP_FAILED);
  const int r = bgra_ ? 2 : 0, b = bgra_ ? 0 : 2;
  for (uint32_t y = 0; y < extent_.height; ++y) {
    uint8_t* row = dst + size_t(y) * extent_.width * 4;
    for (uint32_t x = 0; x < extent_.width; ++x) {
      const bool inside = x < image.width && y < image.height;
      const uint8_t* s = inside ? &image.rgba[(size_t(y) * image.width + x) * 4] : fill;
      row[4 * x + r] = s[0];
      row[4 * x + 1] = s[1];
      row[4 * x + b] = s[2];
      row[4 * x + 3] = 255;
    }
  }
}

void Swapchain::record(VkCommandBuffer cmd, uint32_t index) const {
  VkImage image = images_[index];
  // The acquire semaphore is waited on at the transfer stage; the layout transition is chained
  // to that wait through the same stage.
  imageBarrier(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
               VK_ACCESS_TRANSFER_WRITE_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {extent_.width, extent_.height, 1};
  vkCmdCopyBufferToImage(cmd, staging_.handle(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                         &region);
  imageBarrier(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
               VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
               VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
}

void Swapchain::submit(uint32_t index) {
  SM_VK(vkResetCommandBuffer(cmd_, 0));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  SM_VK(vkBeginCommandBuffer(cmd_, &bi));
  record(cmd_, index);
  SM_VK(vkEndCommandBuffer(cmd_));
  VkFence fence = frameDone_.get();
  SM_VK(vkResetFences(ctx_.device(), 1, &fence));
  VkSemaphore wait = acquired_.get(), signal = copied_[index].get();
  VkPipelineStageFlags stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.waitSemaphoreCount = 1;
  si.pWaitSemaphores = &wait;
  si.pWaitDstStageMask = &stage;
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd_;
  si.signalSemaphoreCount = 1;
  si.pSignalSemaphores = &signal;
  {
    auto queue = ctx_.lockQueue();
    SM_VK(vkQueueSubmit(ctx_.queue(), 1, &si, fence));
  }
  submitted_ = true;
}

PresentResult Swapchain::present(const HostImage& image, const uint8_t fill[4]) {
  if (!swapchain_) return PresentResult::OutOfDate;
  if (image.rgba.size() < size_t(image.width) * image.height * 4)
    throw VulkanError("present: image smaller than its size says", VK_ERROR_UNKNOWN);
  VkFence fence = frameDone_.get();
  // One frame in flight: the previous copy must be done before its staging buffer and acquire
  // semaphore are used again.
  if (submitted_) SM_VK(vkWaitForFences(ctx_.device(), 1, &fence, VK_TRUE, UINT64_MAX));
  uint32_t index = 0;
  VkResult r = vkAcquireNextImageKHR(ctx_.device(), swapchain_, UINT64_MAX, acquired_.get(),
                                     VK_NULL_HANDLE, &index);
  if (r == VK_ERROR_OUT_OF_DATE_KHR) return PresentResult::OutOfDate;
  if (r != VK_SUBOPTIMAL_KHR) SM_VK(r);
  const bool suboptimal = r == VK_SUBOPTIMAL_KHR;
  fillStaging(image, fill);
  submit(index);
  VkSemaphore wait = copied_[index].get();
  VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &wait;
  pi.swapchainCount = 1;
  pi.pSwapchains = &swapchain_;
  pi.pImageIndices = &index;
  {
    auto queue = ctx_.lockQueue();
    r = vkQueuePresentKHR(ctx_.queue(), &pi);
  }
  if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR || suboptimal)
    return PresentResult::OutOfDate;
  SM_VK(r);
  return PresentResult::Presented;
}

}  // namespace sm::vk
