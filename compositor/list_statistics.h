// Per-rank statistics of a frame's fragment lists, gathered on the device in one pass over the
// counts (list_stats.comp): the longest list picks the counter encoding; fragments and non-empty
// pixels are what the paper reports per rank.
#pragma once

#include "vk/buffer.h"
#include "vk/pipeline.h"

namespace sm::comp {

struct ListTotals {
  uint32_t longest = 0;
  uint64_t nonEmptyPixels = 0;
  uint64_t fragments = 0;
};

class ListStatistics {
 public:
  explicit ListStatistics(const vk::Context& ctx);
  // Records the pass over `pixels` counts at `counts`; read() after the submission completed.
  void record(VkCommandBuffer cmd, VkDeviceAddress counts, uint32_t pixels) const;
  ListTotals read() const;

 private:
  vk::ComputePipeline pipeline_;
  vk::Buffer result_;
};

}  // namespace sm::comp
