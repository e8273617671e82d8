// Small helpers for the compositor's device buffers and command recording.
#pragma once

#include <string>

#include "vk/buffer.h"

namespace sm::comp {

// Grows `b` to at least `bytes` (with a quarter of headroom, so that slowly rising fragment counts
// do not reallocate every frame); never shrinks. Counts reallocations in `allocations`.
inline void growBuffer(vk::Buffer& b, const vk::Context& ctx, uint64_t bytes, vk::MemoryUse use,
                       const std::string& name, uint64_t& allocations) {
  if (b.valid() && b.size() >= bytes) return;
  b = vk::Buffer(ctx, bytes + bytes / 4, vk::kStorageUsage, use, name);
  ++allocations;
}

// Orders this submission after the compute and transfer work of earlier ones (buffers are reused
// from frame to frame).
void previousWorkBarrier(VkCommandBuffer cmd);
// Between a transfer that writes a buffer and one that reads it.
void transferBarrier(VkCommandBuffer cmd);
// Makes compute and transfer writes visible to the host once the submission's fence has signalled.
void hostReadBarrier(VkCommandBuffer cmd);
// Makes host writes (to Upload buffers) visible to transfers and shaders of this submission.
void hostWriteBarrier(VkCommandBuffer cmd);
using vk::copyBuffer;

}  // namespace sm::comp
