#include "compositor/list_statistics.h"

#include "compositor/device_util.h"
#include "compositor_shaders.h"
#include "exchange_types.h"

namespace sm::comp {

ListStatistics::ListStatistics(const vk::Context& ctx)
    : pipeline_(ctx, {"list_stats", spv::list_stats(), {}, sizeof(DcStatsPush), false}),
      result_(ctx, 3 * sizeof(uint32_t), vk::kStorageUsage, vk::MemoryUse::Readback,
              "list statistics") {}

void ListStatistics::record(VkCommandBuffer cmd, VkDeviceAddress counts, uint32_t pixels) const {
  vk::fillZero(cmd, result_);
  vk::transferToComputeBarrier(cmd);
  constexpr uint32_t kPixelsPerGroup = 256 * 16;  // list_stats.comp: workgroup x pixels each
  pipeline_.dispatchItems(cmd, pixels, kPixelsPerGroup,
                          DcStatsPush{counts, result_.address(), pixels});
  hostReadBarrier(cmd);
}

ListTotals ListStatistics::read() const {
  uint32_t r[3];
  result_.download(r, sizeof r);
  return {r[0], r[1], r[2]};
}

}  // namespace sm::comp
