// Deep compositing over several ranks: the paper's five steps.
//   1) list statistics, prefix sum over this rank's counts, compaction of its fragments into one
//      send buffer in exchange-position order (each destination's share contiguous; with
//      interleaved ownership the counts are first permuted into that order);
//   2) counts exchanged with alltoallv, packed at 2, 4, 8 or 32 bits from the longest list of any
//      rank (encode/decode on the device), each destination's words sent as they are or as runs of
//      zero words where that is smaller (count_codec.h; a first alltoallv sends the sizes);
//   3) prefix sum over the received counts, second alltoallv moving the fragments;
//   4) k-way merge by depth of each owned pixel's R lists (composite_deep.comp);
//   5) owned pixels gathered on rank 0 (and put back in image order).
// Transfers are host-staged: device buffers are copied to Readback buffers that the communicator
// reads, and from Upload buffers it wrote. Every buffer grows and never shrinks.
#pragma once

#include <chrono>
#include <vector>

#include <glm/vec4.hpp>

#include "comm/communicator.h"
#include "compositor/exchange_plan.h"
#include "compositor/list_statistics.h"
#include "compositor/prefix_sum.h"
#include "vk/buffer.h"
#include "vk/pipeline.h"

namespace sm::comp {

struct CompositeStats;
struct CompositorOptions;

// Fragment lists on this rank as the renderer left them.
struct ListsView {
  const vk::Buffer* fragments = nullptr;
  const vk::Buffer* counts = nullptr;
  const vk::Buffer* offsets = nullptr;  // two-pass list starts; nullptr: fixed K per pixel
  uint32_t fixedK = 0;
};

class DeepExchange {
 public:
  DeepExchange(const vk::Context& ctx, comm::Communicator& comm, uint32_t pixels,
               const CompositorOptions& options, PrefixSum& scan, ListStatistics& listStats,
               uint64_t& allocations);
  // Composites every rank's lists; fills `image` on rank 0 (left untouched elsewhere).
  void run(const ListsView& lists, std::vector<glm::vec4>& image, CompositeStats& stats);

 private:
  using Clock = std::chrono::steady_clock;
  void prepare(const ListsView& lists, CompositeStats& stats);
  void compactAndEncode(const ListsView& lists);
  void exchangeCounts(CompositeStats& stats);
  void transferCounts(CompositeStats& stats);
  void encodeCountPayloads();
  void planCountReceive();
  void expandCountPayloads();
  void exchangeFragments(CompositeStats& stats);
  void compositeOwned();
  void gather(std::vector<glm::vec4>& image);
  void setCounterBits(uint32_t bits);
  bool interleaved() const { return ranges_.ownership() == PixelOwnership::Interleaved; }
  // This rank's counts in exchange-position order: the renderer's own buffer under Ranges.
  const vk::Buffer& positionCounts(const ListsView& lists) const;
  void grow(vk::Buffer& b, uint64_t bytes, vk::MemoryUse use, const char* name);

  const vk::Context& ctx_;
  comm::Communicator& comm_;
  const uint32_t pixels_;
  const PixelRanges ranges_;
  const int rank_, ranks_;
  const uint32_t owned_;  // pixels this rank composites
  const uint32_t fragmentBytes_;
  const uint32_t forcedBits_;
  PrefixSum& scan_;
  ListStatistics& listStats_;
  uint64_t& allocations_;
  vk::ComputePipeline compact_, encode_, decode_, composite_, permute_;
  CountExchange counts_;                             // plan for the current counter width
  std::vector<uint64_t> sendIndices_, recvIndices_;  // scan entries where each rank's share starts
  std::vector<uint64_t> sendBegin_, recvBegin_;
  uint64_t sendTotal_ = 0, recvTotal_ = 0;
  // Step 1-2 (sizes fixed by the image and rank count)
  vk::Buffer sendCounts_;  // interleaved: this rank's counts in position order
  vk::Buffer sendOffsets_, sendBoundaries_, sendWords_, segments_, sendCountStage_;
  vk::Buffer recvCountStage_, recvWords_, recvCounts_, recvOffsets_, recvBoundaries_;
  vk::Buffer ownedImage_;
  std::vector<glm::vec4> gathered_;  // rank 0, interleaved: the image in position order
  // Step 2 on the host: headers and payloads (count_codec.h) sent and received.
  struct Payloads {
    std::vector<uint64_t> bytes, offsets;  // per rank
    void resize(size_t ranks) {
      bytes.resize(ranks);
      offsets.resize(ranks);
    }
  };
  std::vector<uint64_t> headerSend_, headerRecv_;
  Payloads payloadSend_, payloadRecv_;
  std::vector<uint32_t> countSend_, countRecv_;
  // Step 3 (grow with the fragment totals)
  vk::Buffer sendFragments_, sendFragmentStage_, recvFragmentStage_, recvFragments_;
};

}  // namespace sm::comp
