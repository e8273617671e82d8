// Exclusive prefix sum of uint32 values on the device (block scan, recursive over block totals).
#pragma once

#include <memory>
#include <vector>

#include "vk/buffer.h"
#include "vk/pipeline.h"

namespace sm::comp {

// The most fragments (or list slots) one rank's lists may hold: shaders index them with 32-bit
// integers, which SPIR-V access chains may read as signed.
inline constexpr uint32_t kMaxListIndex = 0x7fffffffu;

class PrefixSum {
 public:
  explicit PrefixSum(const vk::Context& ctx);
  // Records an in-place exclusive scan of n values at `values`. Buffers grow, never shrink.
  void record(VkCommandBuffer cmd, VkDeviceAddress values, uint32_t n);
  // The total of the last scan, once its commands have completed. Throws std::overflow_error,
  // naming what was summed, beyond kMaxListIndex (past 32 bits the offsets have wrapped).
  uint32_t downloadTotal(const char* what) const;

 private:
  void recordLevel(VkCommandBuffer cmd, VkDeviceAddress values, uint32_t n, size_t level);
  const vk::Context& ctx_;
  vk::ComputePipeline blocks_, add_;
  std::vector<vk::Buffer> sums_;  // one per level
  vk::Buffer total_;
};

}  // namespace sm::comp
