#include "compositor/host_lists.h"

#include <stdexcept>
#include <string>

#include "compositor/device_util.h"
#include "compositor_shaders.h"
#include "exchange_types.h"

namespace sm::comp {

ListWriter::ListWriter(DeepCompositor& c)
    : compositor_(c),
      ctx_(c.context()),
      pipeline_(ctx_, {"write_lists",
                       spv::write_lists(),
                       {{100, c.modeConstant()}, {101, c.encodingConstant()}},
                       sizeof(DcWritePush),
                       false}) {}

void ListWriter::write(const HostLists& lists) {
  const uint64_t pixels = uint64_t(compositor_.width()) * compositor_.height();
  if (lists.counts.size() != pixels)
    throw std::invalid_argument("host lists: " + std::to_string(lists.counts.size()) +
                                " counts for " + std::to_string(pixels) + " pixels");
  std::vector<uint32_t> offsets(pixels);
  uint64_t total = 0;
  for (uint64_t p = 0; p < pixels; ++p) {
    offsets[p] = uint32_t(total);
    total += lists.counts[p];
  }
  if (total != lists.fragments.size())
    throw std::invalid_argument("host lists: counts add up to " + std::to_string(total) +
                                " fragments, but " + std::to_string(lists.fragments.size()) +
                                " are given");
  const auto upload = vk::MemoryUse::Upload;
  growBuffer(raw_, ctx_, total * sizeof(DcFragment), upload, "host fragments", allocations_);
  growBuffer(rawOffsets_, ctx_, pixels * 4, upload, "host list offsets", allocations_);
  growBuffer(rawCounts_, ctx_, pixels * 4, upload, "host list counts", allocations_);
  raw_.upload(lists.fragments.data(), total * sizeof(DcFragment));
  rawOffsets_.upload(offsets.data(), pixels * 4);
  rawCounts_.upload(lists.counts.data(), pixels * 4);
  if (compositor_.options().mode == ListMode::TwoPass) {
    dispatch(true, uint32_t(pixels));
    compositor_.prepareLists();
  }
  dispatch(false, uint32_t(pixels));
}

void ListWriter::dispatch(bool countOnly, uint32_t pixels) {
  DeviceLists l = compositor_.lists();
  DcWritePush p{raw_.address(),
                rawOffsets_.address(),
                rawCounts_.address(),
                l.capacities,
                l.offsets,
                l.counts,
                l.fragments,
                pixels,
                l.fixedK,
                countOnly ? 1u : 0u};
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    previousWorkBarrier(cmd);
    hostWriteBarrier(cmd);
    pipeline_.dispatchItems(cmd, pixels, 64, p);
  });
}

}  // namespace sm::comp
