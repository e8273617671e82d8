#include "vk/buffer.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <utility>

#include "vk/vk_error.h"

namespace sm::vk {
namespace {
constexpr VkDeviceSize kMinSize = 16;
constexpr VkDeviceSize kStagingChunk = 64ull << 20;

std::string bytesText(uint64_t bytes) {
  if (bytes == UINT64_MAX) return "unlimited";
  char text[32];
  if (bytes >= (uint64_t(1) << 30))
    std::snprintf(text, sizeof text, "%.2f GiB", double(bytes) / double(1 << 30));
  else if (bytes >= (uint64_t(1) << 20))
    std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / double(1 << 20));
  else
    std::snprintf(text, sizeof text, "%.1f KiB", double(bytes) / 1024.0);
  return text;
}

// Bytes in both units: the exact count shows how far past a limit a buffer is.
std::string sizeText(uint64_t bytes) {
  return bytesText(bytes) + " (" + std::to_string(bytes) + " bytes)";
}

void refuseOverLimit(const Context& ctx, const std::string& name, uint64_t bytes,
                     uint64_t allocationBytes) {
  const std::string why = bufferSizeError(name, bytes, allocationBytes, ctx.bufferLimits());
  if (!why.empty())
    throw BufferLimitError(why, VK_ERROR_OUT_OF_DEVICE_MEMORY, allocationBytes,
                           ctx.deviceMemoryInUse());
}
}  // namespace

std::string bufferSizeError(const std::string& name, uint64_t bytes, uint64_t allocationBytes,
                            const BufferLimits& limits) {
  const bool buffer = bytes > limits.maxBufferSize;
  if (!buffer && allocationBytes <= limits.maxAllocationSize) return {};
  const uint64_t size = buffer ? bytes : allocationBytes;
  const uint64_t limit = buffer ? limits.maxBufferSize : limits.maxAllocationSize;
  // A rank's buffers shrink with its share of the mesh: this many times the ranks bring this one
  // under the limit (size > limit >= 0, so size >= 1).
  const uint64_t times = (size - 1) / std::max<uint64_t>(limit, 1) + 1;
  return "buffer '" + name + "' needs " + sizeText(size) + ", more than the device's " +
         (buffer ? "largest buffer (maxBufferSize, "
                 : "largest allocation (maxMemoryAllocationSize, ") +
         sizeText(limit) + "); use more ranks (at least " + std::to_string(times) +
         " times as many)";
}

Buffer::Buffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use,
               const std::string& name)
    : ctx_(&ctx), size_(std::max(size, kMinSize)), name_(name) {
  refuseOverLimit(ctx, name, size_, size_);  // before the buffer is created
  VkDevice dev = ctx.device();
  VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bci.size = size_;
  bci.usage = usage | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
  bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buf;
  SM_VK(vkCreateBuffer(dev, &bci, nullptr, &buf));
  buffer_ = DeviceHandle<VkBuffer>(dev, buf, vkDestroyBuffer);
  ctx.setName(VK_OBJECT_TYPE_BUFFER, uint64_t(buf), name);

  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(dev, buf, &req);
  refuseOverLimit(ctx, name, size_, req.size);  // before its memory is allocated
  VkMemoryPropertyFlags want = 0, avoid = 0;
  switch (use) {
    case MemoryUse::Device:
      want = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
      break;
    case MemoryUse::Upload:
      want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      avoid = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
      break;
    case MemoryUse::Readback:
      want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_CACHED_BIT |
             VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      break;
  }
  uint32_t type;
  try {
    type = ctx.memoryType(req.memoryTypeBits, want, avoid);
  } catch (const VulkanError&) {
    // Host buffers are read and written through a persistent mapping without flushes, so they
    // must be coherent (a cached, non-coherent type, listed first on some mobile drivers, would
    // leave them unmapped); the spec guarantees a visible, coherent type.
    type = ctx.memoryType(req.memoryTypeBits, use == MemoryUse::Device
                                                  ? 0
                                                  : VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                        VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  }
  VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.pNext = &flags;
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = type;
  auto outOfMemory = [&](VkResult r) {
    const uint64_t used = ctx.deviceMemoryInUse();
    return DeviceMemoryError("cannot allocate " + bytesText(req.size) + " of device memory for " +
                                 name + " (" + bytesText(used) + " in use, " +
                                 bytesText(ctx.deviceMemoryLimit()) + " usable)",
                             r, req.size, used);
  };
  if (!ctx.reserveDeviceMemory(req.size)) throw outOfMemory(VK_ERROR_OUT_OF_DEVICE_MEMORY);
  VkDeviceMemory mem;
  VkResult r = vkAllocateMemory(dev, &ai, nullptr, &mem);
  if (r != VK_SUCCESS) {
    ctx.releaseDeviceMemory(req.size);
    throw outOfMemory(r);
  }
  memory_ = DeviceHandle<VkDeviceMemory>(dev, mem, vkFreeMemory);
  ctx.setName(VK_OBJECT_TYPE_DEVICE_MEMORY, uint64_t(mem), name);
  VkResult bound = vkBindBufferMemory(dev, buf, mem, 0);
  if (bound != VK_SUCCESS) {
    ctx.releaseDeviceMemory(req.size);  // no destructor runs for a constructor that throws
    SM_VK(bound);
  }
  reserved_ = req.size;

  VkMemoryPropertyFlags got;
  {
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice(), &mp);
    got = mp.memoryTypes[type].propertyFlags;
  }
  bool mappable =
      (got & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) && (got & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  if (use == MemoryUse::Device && ctx.forceStaging()) mappable = false;
  if (mappable) {
    VkResult m = vkMapMemory(dev, mem, 0, VK_WHOLE_SIZE, 0, &mapped_);
    if (m != VK_SUCCESS) {
      ctx.releaseDeviceMemory(std::exchange(reserved_, 0));
      SM_VK(m);
    }
  }

  VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
  info.buffer = buf;
  address_ = vkGetBufferDeviceAddress(dev, &info);
}

Buffer& Buffer::operator=(Buffer&& o) noexcept {
  if (this != &o) {
    if (mapped_ && memory_) vkUnmapMemory(ctx_->device(), memory_.get());
    if (reserved_) ctx_->releaseDeviceMemory(reserved_);
    reserved_ = std::exchange(o.reserved_, 0);
    buffer_ = std::move(o.buffer_);
    memory_ = std::move(o.memory_);
    ctx_ = o.ctx_;
    size_ = o.size_;
    address_ = o.address_;
    mapped_ = std::exchange(o.mapped_, nullptr);
    name_ = std::move(o.name_);
  }
  return *this;
}

Buffer::~Buffer() {
  if (mapped_ && memory_) vkUnmapMemory(ctx_->device(), memory_.get());
  if (reserved_) ctx_->releaseDeviceMemory(reserved_);
}

void Buffer::upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  if (bytes == 0) return;
  if (offset + bytes > size_)
    throw VulkanError("upload past the end of buffer " + name_, VK_ERROR_UNKNOWN);
  if (mapped_) {
    std::memcpy(static_cast<uint8_t*>(mapped_) + offset, data, bytes);
    return;
  }
  VkDeviceSize chunk = std::min(bytes, kStagingChunk);
  Buffer staging(*ctx_, chunk, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Upload,
                 name_ + " (staging)");
  for (VkDeviceSize done = 0; done < bytes; done += chunk) {
    VkDeviceSize n = std::min(chunk, bytes - done);
    std::memcpy(staging.mapped(), static_cast<const uint8_t*>(data) + done, n);
    ctx_->submitAndWait([&](VkCommandBuffer cmd) {
      VkBufferCopy copy{0, offset + done, n};
      vkCmdCopyBuffer(cmd, staging.handle(), handle(), 1, &copy);
    });
  }
}

void Buffer::download(void* data, VkDeviceSize bytes, VkDeviceSize offset) const {
  if (bytes == 0) return;
  if (offset + bytes > size_)
    throw VulkanError("download past the end of buffer " + name_, VK_ERROR_UNKNOWN);
  if (mapped_) {
    std::memcpy(data, static_cast<const uint8_t*>(mapped_) + offset, bytes);
    return;
  }
  VkDeviceSize chunk = std::min(bytes, kStagingChunk);
  Buffer staging(*ctx_, chunk, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback,
                 name_ + " (readback)");
  for (VkDeviceSize done = 0; done < bytes; done += chunk) {
    VkDeviceSize n = std::min(chunk, bytes - done);
    ctx_->submitAndWait([&](VkCommandBuffer cmd) {
      VkBufferCopy copy{offset + done, 0, n};
      vkCmdCopyBuffer(cmd, handle(), staging.handle(), 1, &copy);
    });
    std::memcpy(static_cast<uint8_t*>(data) + done, staging.mapped(), n);
  }
}

void Buffer::fill(uint32_t value) {
  ctx_->submitAndWait(
      [&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, handle(), 0, VK_WHOLE_SIZE, value); });
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags srcAccess,
                   VkPipelineStageFlags dst, VkAccessFlags dstAccess) {
  VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  mb.srcAccessMask = srcAccess;
  mb.dstAccessMask = dstAccess;
  vkCmdPipelineBarrier(cmd, src, dst, 0, 1, &mb, 0, nullptr, 0, nullptr);
}

void computeBarrier(VkCommandBuffer cmd) {
  memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT,
                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

void transferToComputeBarrier(VkCommandBuffer cmd) {
  memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

void computeToTransferBarrier(VkCommandBuffer cmd) {
  memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT,
                VK_PIPELINE_STAGE_TRANSFER_BIT,
                VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
}

void copyBuffer(VkCommandBuffer cmd, const Buffer& src, uint64_t srcOffset, const Buffer& dst,
                uint64_t dstOffset, uint64_t bytes) {
  if (bytes == 0) return;
  VkBufferCopy c{srcOffset, dstOffset, bytes};
  vkCmdCopyBuffer(cmd, src.handle(), dst.handle(), 1, &c);
}

void copyRegions(VkCommandBuffer cmd, const Buffer& src, const Buffer& dst,
                 std::span<const VkBufferCopy> regions) {
  if (!regions.empty())
    vkCmdCopyBuffer(cmd, src.handle(), dst.handle(), uint32_t(regions.size()), regions.data());
}

void fillZero(VkCommandBuffer cmd, const Buffer& b) {
  vkCmdFillBuffer(cmd, b.handle(), 0, VK_WHOLE_SIZE, 0);
}

}  // namespace sm::vk
