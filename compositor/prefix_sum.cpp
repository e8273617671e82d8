#include "compositor/prefix_sum.h"

#include <cstdint>
#include <stdexcept>
#include <string>

#include "compositor_shaders.h"

namespace sm::comp {
namespace {
constexpr uint32_t kBlock = 1024;
struct Push {
  uint64_t values, sums;
  uint32_t n;
};
}  // namespace

PrefixSum::PrefixSum(const vk::Context& ctx)
    : ctx_(ctx),
      blocks_(ctx, {"scan_blocks", spv::scan_blocks(), {}, sizeof(Push), false}),
      add_(ctx, {"scan_add", spv::scan_add(), {}, sizeof(Push), false}),
      total_(ctx, sizeof(uint64_t), vk::kStorageUsage, vk::MemoryUse::Readback, "scan total") {}

void PrefixSum::recordLevel(VkCommandBuffer cmd, VkDeviceAddress values, uint32_t n, size_t level) {
  const uint32_t groups = vk::groupsFor(n, kBlock);
  if (sums_.size() <= level) sums_.emplace_back();
  if (!sums_[level].valid() || sums_[level].size() < groups * sizeof(uint32_t))
    sums_[level] = vk::Buffer(ctx_, uint64_t(groups) * 2 * sizeof(uint32_t), vk::kStorageUsage,
                              vk::MemoryUse::Device, "scan level " + std::to_string(level));
  VkDeviceAddress sums = sums_[level].address();
  blocks_.dispatchItems(cmd, n, kBlock, Push{values, groups == 1 ? total_.address() : sums, n});
  vk::computeBarrier(cmd);
  if (groups == 1) return;
  recordLevel(cmd, sums, groups, level + 1);
  add_.dispatchItems(cmd, n, kBlock, Push{values, sums, n});
  vk::computeBarrier(cmd);
}

void PrefixSum::record(VkCommandBuffer cmd, VkDeviceAddress values, uint32_t n) {
  if (n == 0) {
    vk::fillZero(cmd, total_);
    vk::transferToComputeBarrier(cmd);
    return;
  }
  recordLevel(cmd, values, n, 0);
}

uint32_t PrefixSum::downloadTotal(const char* what) const {
  uint64_t total = 0;
  total_.download(&total, sizeof total);
  if (total > kMaxListIndex)
    throw std::overflow_error(
        std::string("compositor: ") + what + " add up to " + std::to_string(total) +
        ", more than the lists' 32-bit indices reach (" + std::to_string(kMaxListIndex) +
        "); render fewer pixels per rank or use fixed-length lists (--lists merge)");
  return uint32_t(total);
}

}  // namespace sm::comp
