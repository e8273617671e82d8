// Buffers with their own memory, reached from shaders by device address (buffer_reference), so no
// descriptor range limit applies (lavapipe's maxStorageBufferRange is 128 MiB).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "vk/context.h"

namespace sm::vk {

enum class MemoryUse {
  Device,    // device-local; mapped only where the device makes it host-visible (and not
             // forceStaging)
  Upload,    // host-visible, written by the CPU (staging, per-frame parameters)
  Readback,  // host-visible and cached, read by the CPU (host-staged MPI, images)
};

// Empty when a buffer `name` of `bytes`, whose memory takes `allocationBytes`, is within `limits`;
// else one line naming the buffer, its size, the limit it passes and what would fit. Buffer checks
// this before it creates the buffer (its size standing for the memory too) and again before it
// allocates the memory the device asks for, throwing BufferLimitError.
std::string bufferSizeError(const std::string& name, uint64_t bytes, uint64_t allocationBytes,
                            const BufferLimits& limits);

class Buffer {
 public:
  Buffer() = default;
  // size 0 is rounded up so that every buffer has a valid address. Throws BufferLimitError for a
  // size past the device's limits (bufferSizeError), DeviceMemoryError when memory runs out.
  Buffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use,
         const std::string& name);
  Buffer(Buffer&& o) noexcept { *this = std::move(o); }
  Buffer& operator=(Buffer&&) noexcept;
  ~Buffer();

  VkBuffer handle() const { return buffer_.get(); }
  VkDeviceAddress address() const { return address_; }
  VkDeviceSize size() const { return size_; }
  void* mapped() const { return mapped_; }
  bool valid() const { return bool(buffer_); }
  const std::string& name() const { return name_; }

  // Copies to or from the buffer: memcpy where it is mapped, otherwise through a staging buffer
  // and a transfer on the queue (waits).
  void upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
  template <typename T>
  void upload(std::span<const T> v, VkDeviceSize offset = 0) {
    upload(v.data(), v.size_bytes(), offset);
  }
  void download(void* data, VkDeviceSize bytes, VkDeviceSize offset = 0) const;
  template <typename T>
  std::vector<T> download() const {
    std::vector<T> v(size_ / sizeof(T));
    download(v.data(), v.size() * sizeof(T));
    return v;
  }
  // Fills with a 32-bit pattern on the device (vkCmdFillBuffer) and waits.
  void fill(uint32_t value);

 private:
  const Context* ctx_ = nullptr;
  DeviceHandle<VkBuffer> buffer_;
  DeviceHandle<VkDeviceMemory> memory_;
  VkDeviceSize size_ = 0;
  VkDeviceAddress address_ = 0;
  void* mapped_ = nullptr;
  std::string name_;
  VkDeviceSize reserved_ = 0;  // counted against the context's device memory limit
};

// Standard usage for storage buffers reached by address, that can also be copied to and from.
inline constexpr VkBufferUsageFlags kStorageUsage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
    VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;

// A device buffer holding `data` (at least 16 bytes).
template <typename T>
Buffer makeBuffer(const Context& ctx, std::span<const T> data, const std::string& name,
                  VkBufferUsageFlags extraUsage = 0) {
  Buffer b(ctx, data.size_bytes(), kStorageUsage | extraUsage, MemoryUse::Device, name);
  if (!data.empty()) b.upload(data.data(), data.size_bytes());
  return b;
}

// A global memory barrier from (src, srcAccess) to (dst, dstAccess); the named ones below are the
// common cases.
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags srcAccess,
                   VkPipelineStageFlags dst, VkAccessFlags dstAccess);
// Memory barrier between dependent compute (and transfer) work on the queue.
void computeBarrier(VkCommandBuffer cmd);
void transferToComputeBarrier(VkCommandBuffer cmd);
void computeToTransferBarrier(VkCommandBuffer cmd);

// Records a buffer copy; zero-byte copies are skipped (Vulkan forbids them).
void copyBuffer(VkCommandBuffer cmd, const Buffer& src, uint64_t srcOffset, const Buffer& dst,
                uint64_t dstOffset, uint64_t bytes);
// Records several copies from src to dst in one command; none when `regions` is empty.
void copyRegions(VkCommandBuffer cmd, const Buffer& src, const Buffer& dst,
                 std::span<const VkBufferCopy> regions);
// Records zeroing the whole buffer (a transfer write).
void fillZero(VkCommandBuffer cmd, const Buffer& b);

}  // namespace sm::vk
