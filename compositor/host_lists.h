// Fragment lists produced on the host (a CPU renderer, tests, benchmarks), written into a
// compositor's device lists through the same device interface a renderer's shader uses
// (write_lists.comp includes fragment_list.glsl): zero-opacity fragments are dropped and
// fixed-length overflow is dropped or merged exactly as on the device.
#pragma once

#include <vector>

#include "compositor/deep_compositor.h"

namespace sm::comp {

// One rank's fragments per pixel, each pixel's in visibility order (front to back).
struct HostLists {
  std::vector<uint32_t> counts;       // per pixel
  std::vector<DcFragment> fragments;  // all pixels' lists, concatenated in pixel order
};

class ListWriter {
 public:
  explicit ListWriter(DeepCompositor& compositor);
  // Two-pass lists: the counting pass, prepareLists() and the writing pass; fixed-length lists:
  // the writing pass. Upload buffers grow and never shrink.
  void write(const HostLists& lists);

 private:
  void dispatch(bool countOnly, uint32_t pixels);
  DeepCompositor& compositor_;
  const vk::Context& ctx_;
  vk::ComputePipeline pipeline_;
  vk::Buffer raw_, rawOffsets_, rawCounts_;
  uint64_t allocations_ = 0;
};

}  // namespace sm::comp
