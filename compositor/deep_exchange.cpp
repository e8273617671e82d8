#include "compositor/deep_exchange.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "compositor/count_codec.h"
#include "compositor/deep_compositor.h"
#include "compositor/device_util.h"
#include "compositor_shaders.h"
#include "exchange_types.h"

namespace sm::comp {
namespace {

using vk::MemoryUse;

double msBetween(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// Copies the uint32 at each of `indices` in `src` to consecutive slots of `dst`, skipping indices
// at or past `n` (their value is the scan total, filled in on the host).
void copyBoundaries(VkCommandBuffer cmd, const vk::Buffer& src, uint64_t n, const vk::Buffer& dst,
                    const std::vector<uint64_t>& indices) {
  std::vector<VkBufferCopy> regions;
  for (size_t r = 0; r < indices.size(); ++r)
    if (indices[r] < n) regions.push_back({indices[r] * 4, uint64_t(r) * 4, 4});
  vk::copyRegions(cmd, src, dst, regions);
}

// The scan's value at each index (the total where the index is past the end), then the total.
void readBoundaries(const vk::Buffer& b, uint64_t n, uint64_t total,
                    const std::vector<uint64_t>& indices, std::vector<uint64_t>& out) {
  std::vector<uint32_t> v(indices.size());
  b.download(v.data(), v.size() * 4);
  out.resize(indices.size() + 1);
  for (size_t r = 0; r < indices.size(); ++r) out[r] = indices[r] < n ? v[r] : total;
  out.back() = total;
}

}  // namespace

DeepExchange::DeepExchange(const vk::Context& ctx, comm::Communicator& comm, uint32_t pixels,
                           const CompositorOptions& o, PrefixSum& scan, ListStatistics& listStats,
                           uint64_t& allocations)
    : ctx_(ctx),
      comm_(comm),
      pixels_(pixels),
      ranges_(pixels, comm.size(), o.ownership),
      rank_(comm.rank()),
      ranks_(comm.size()),
      owned_(uint32_t(ranges_.count(comm.rank()))),
      fragmentBytes_(fragmentBytes(o.encoding)),
      forcedBits_(o.counterBits),
      scan_(scan),
      listStats_(listStats),
      allocations_(allocations) {
  const uint32_t enc = o.encoding == Encoding::Float ? DC_ENCODING_FLOAT : DC_ENCODING_RGBA8;
  const std::vector<vk::SpecConstant> spec = {{101, enc}};
  compact_ = vk::ComputePipeline(ctx, {"compact", spv::compact(), spec, sizeof(DcCompactPush)});
  encode_ =
      vk::ComputePipeline(ctx, {"encode_counts", spv::encode_counts(), spec, sizeof(DcEncodePush)});
  decode_ =
      vk::ComputePipeline(ctx, {"decode_counts", spv::decode_counts(), spec, sizeof(DcDecodePush)});
  if (interleaved())
    permute_ = vk::ComputePipeline(
        ctx, {"permute_counts", spv::permute_counts(), {}, sizeof(DcPermutePush)});
  composite_ = vk::ComputePipeline(ctx, {"composite_deep",
                                         spv::composite_deep(),
                                         {{0, std::max(o.registerLists, 1u)}, {101, enc}},
                                         sizeof(DcDeepPush)});
  const uint64_t R = uint64_t(ranks_), P = pixels, n = owned_;
  for (int r = 0; r < ranks_; ++r) {
    sendIndices_.push_back(ranges_.begin(r));  // first position of destination r
    recvIndices_.push_back(uint64_t(r) * n);   // first list from source r
  }
  if (interleaved()) grow(sendCounts_, P * 4, MemoryUse::Device, "send counts (position order)");
  grow(sendOffsets_, P * 4, MemoryUse::Device, "send offsets");
  grow(sendBoundaries_, R * 4, MemoryUse::Readback, "send boundaries");
  grow(sendWords_, (encodedWords(P, 8) + R) * 4, MemoryUse::Device, "packed counts");
  grow(segments_, (R + 1) * 8, MemoryUse::Upload, "count segments");
  grow(sendCountStage_, P * 4, MemoryUse::Readback, "count send stage");
  grow(recvCountStage_, R * n * 4, MemoryUse::Upload, "count receive stage");
  grow(recvWords_, R * n * 4, MemoryUse::Device, "received packed counts");
  grow(recvCounts_, R * n * 4, MemoryUse::Device, "received counts");
  grow(recvOffsets_, R * n * 4, MemoryUse::Device, "received offsets");
  grow(recvBoundaries_, R * 4, MemoryUse::Readback, "receive boundaries");
  grow(ownedImage_, n * sizeof(glm::vec4), MemoryUse::Readback, "owned pixels");
}

void DeepExchange::grow(vk::Buffer& b, uint64_t bytes, vk::MemoryUse use, const char* name) {
  growBuffer(b, ctx_, bytes, use, name, allocations_);
}

void DeepExchange::setCounterBits(uint32_t bits) {
  if (!counts_.sendWordBegin.empty() && counts_.bits == bits) return;
  counts_ = planCountExchange(ranges_, rank_, bits);
  std::vector<uint32_t> seg(2 * (size_t(ranks_) + 1));
  for (int d = 0; d <= ranks_; ++d) {
    seg[2 * size_t(d)] = uint32_t(ranges_.begin(d));
    seg[2 * size_t(d) + 1] = uint32_t(counts_.sendWordBegin[size_t(d)]);
  }
  segments_.upload(seg.data(), seg.size() * 4);
}

void DeepExchange::run(const ListsView& lists, std::vector<glm::vec4>& image,
                       CompositeStats& stats) {
  auto t0 = Clock::now();
  prepare(lists, stats);
  auto t1 = Clock::now();
  exchangeCounts(stats);
  auto t2 = Clock::now();
  exchangeFragments(stats);
  auto t3 = Clock::now();
  compositeOwned();
  auto t4 = Clock::now();
  gather(image);
  auto t5 = Clock::now();
  stats.timings = {msBetween(t0, t1), msBetween(t1, t2), msBetween(t2, t3), msBetween(t3, t4),
                   msBetween(t4, t5)};
  stats.milliseconds = msBetween(t0, t5);
}

// Step 1: statistics and prefix sum, then (with the global longest list known) compaction.
void DeepExchange::prepare(const ListsView& lists, CompositeStats& stats) {
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    previousWorkBarrier(cmd);
    listStats_.record(cmd, lists.counts->address(), pixels_);
    if (interleaved()) {
      DcPermutePush p{lists.counts->address(), sendCounts_.address(), pixels_,
                      uint32_t(ranks_),        ranges_.byRanks(),     ranges_.base(),
                      ranges_.extra()};
      permute_.dispatchItems(cmd, pixels_, 256 * 16, p);  // permute_counts.comp
      vk::computeToTransferBarrier(cmd);
    }
    copyBuffer(cmd, positionCounts(lists), 0, sendOffsets_, 0, uint64_t(pixels_) * 4);
    vk::transferToComputeBarrier(cmd);
    scan_.record(cmd, sendOffsets_.address(), pixels_);
    vk::computeToTransferBarrier(cmd);
    copyBoundaries(cmd, sendOffsets_, pixels_, sendBoundaries_, sendIndices_);
    hostReadBarrier(cmd);
  });
  ListTotals totals = listStats_.read();
  sendTotal_ = scan_.downloadTotal("this rank's list lengths");
  readBoundaries(sendBoundaries_, pixels_, sendTotal_, sendIndices_, sendBegin_);
  stats.fragments = totals.fragments;
  stats.nonEmptyPixels = totals.nonEmptyPixels;
  stats.longestList = totals.longest;
  const uint64_t longest = comm_.allreduceMax(totals.longest);
  stats.counterBits = chooseCounterBits(longest, forcedBits_);
  setCounterBits(stats.counterBits);
  grow(sendFragments_, sendTotal_ * fragmentBytes_, MemoryUse::Device, "send fragments");
  grow(sendFragmentStage_, sendTotal_ * fragmentBytes_, MemoryUse::Readback, "fragment send stage");
  compactAndEncode(lists);
}

void DeepExchange::compactAndEncode(const ListsView& lists) {
  const uint32_t bits = counts_.bits;
  const uint64_t words = counts_.sendWordBegin.back();
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    previousWorkBarrier(cmd);
    DcCompactPush c{lists.fragments->address(),
                    lists.counts->address(),
                    lists.offsets ? lists.offsets->address() : 0,
                    sendFragments_.address(),
                    sendOffsets_.address(),
                    0,
                    pixels_,
                    lists.fixedK,
                    uint32_t(interleaved()),
                    uint32_t(ranks_),
                    interleaved() ? ranges_.byRanks() : DcDivisor{},
                    ranges_.base(),
                    ranges_.extra()};
    compact_.dispatchItems(cmd, pixels_, 64, c);
    const vk::Buffer& counts = positionCounts(lists);
    if (bits < 32) {
      DcEncodePush e{counts.address(), segments_.address(), sendWords_.address(),
                     uint32_t(ranks_), uint32_t(words),     bits};
      encode_.dispatchItems(cmd, words, 64, e);
    }
    vk::computeToTransferBarrier(cmd);
    copyBuffer(cmd, sendFragments_, 0, sendFragmentStage_, 0, sendTotal_ * fragmentBytes_);
    copyBuffer(cmd, bits < 32 ? sendWords_ : counts, 0, sendCountStage_, 0, words * 4);
    hostReadBarrier(cmd);
  });
}

// Step 2's transfers: each destination's packed words as they are, or their zero-run code where
// that is smaller (count_codec.h), after one header per pair saying which and how long. Received
// codes are expanded into the receive stage, where the device decodes every source's words.
void DeepExchange::transferCounts(CompositeStats& stats) {
  encodeCountPayloads();
  const size_t R = size_t(ranks_);
  headerRecv_.resize(R);
  std::vector<uint64_t> headerBytes(R, kPayloadHeaderBytes), slots(R);
  for (size_t r = 0; r < R; ++r) slots[r] = r * kPayloadHeaderBytes;
  comm_.alltoallv(headerSend_.data(), headerBytes, slots, headerRecv_.data(), headerBytes, slots);
  planCountReceive();
  comm_.alltoallv(countSend_.data(), payloadSend_.bytes, payloadSend_.offsets, countRecv_.data(),
                  payloadRecv_.bytes, payloadRecv_.offsets);
  expandCountPayloads();
  stats.countBytesSent = 0;
  for (size_t d = 0; d < R; ++d)
    if (int(d) != rank_) stats.countBytesSent += kPayloadHeaderBytes + payloadSend_.bytes[d];
}

void DeepExchange::encodeCountPayloads() {
  const size_t R = size_t(ranks_);
  const auto* words = static_cast<const uint32_t*>(sendCountStage_.mapped());
  payloadSend_.resize(R);
  headerSend_.resize(R);
  countSend_.clear();
  countSend_.reserve(1);  // data() of an empty vector may be null
  for (size_t d = 0; d < R; ++d) {
    const std::span<const uint32_t> share(words + counts_.sendWordBegin[d],
                                          counts_.sendWordBegin[d + 1] - counts_.sendWordBegin[d]);
    const CountPayload p = choosePayload(share, counts_.transfer.sendBytes[d]);
    payloadSend_.offsets[d] = countSend_.size() * 4;
    if (p.zeroRuns)
      appendZeroRuns(share, countSend_);
    else  // the words themselves, of which only the bytes holding counters go
      countSend_.insert(countSend_.end(), share.begin(), share.end());
    payloadSend_.bytes[d] = p.bytes;
    headerSend_[d] = payloadHeader(p);
  }
}

// What a peer may send is fixed by the plan: its counters as they are, or a code smaller than
// that. Anything else would overrun the receive stage.
void DeepExchange::planCountReceive() {
  const size_t R = size_t(ranks_);
  const Transfer& t = counts_.transfer;
  payloadRecv_.resize(R);
  uint64_t words = 0;
  for (size_t s = 0; s < R; ++s) {
    const uint64_t bytes = headerRecv_[s] & ~kZeroRunFlag;
    const bool code = headerRecv_[s] & kZeroRunFlag;
    if (code ? bytes % 4 != 0 || bytes >= t.recvBytes[s] : bytes != t.recvBytes[s])
      throw comm::CommError("count exchange: rank " + std::to_string(s) + " announces " +
                            std::to_string(bytes) + " bytes" + (code ? " of zero runs" : "") +
                            ", the plan allows " + std::to_string(t.recvBytes[s]));
    payloadRecv_.bytes[s] = bytes;
    payloadRecv_.offsets[s] = words * 4;
    words += (bytes + 3) / 4;
  }
  countRecv_.resize(std::max<uint64_t>(words, 1));
}

void DeepExchange::expandCountPayloads() {
  auto* stage = static_cast<uint8_t*>(recvCountStage_.mapped());
  for (size_t s = 0; s < size_t(ranks_); ++s) {
    uint8_t* to = stage + s * counts_.wordsPerSource * 4;
    const uint32_t* from = countRecv_.data() + payloadRecv_.offsets[s] / 4;
    const uint64_t bytes = payloadRecv_.bytes[s];
    if (headerRecv_[s] & kZeroRunFlag)
      expandZeroRuns({from, bytes / 4}, {reinterpret_cast<uint32_t*>(to), counts_.wordsPerSource});
    else if (bytes > 0)
      std::memcpy(to, from, bytes);
  }
}

// Step 2 and the prefix sum of step 3: after it, recvBegin_ says where each source's fragments go.
void DeepExchange::exchangeCounts(CompositeStats& stats) {
  transferCounts(stats);
  const uint32_t bits = counts_.bits;
  const uint32_t received = uint32_t(ranks_) * owned_;
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    previousWorkBarrier(cmd);
    hostWriteBarrier(cmd);
    const uint64_t words = uint64_t(ranks_) * counts_.wordsPerSource;
    copyBuffer(cmd, recvCountStage_, 0, bits < 32 ? recvWords_ : recvCounts_, 0, words * 4);
    if (bits < 32) {
      vk::transferToComputeBarrier(cmd);
      DcDecodePush d{recvWords_.address(),
                     recvCounts_.address(),
                     owned_,
                     uint32_t(ranks_),
                     uint32_t(counts_.wordsPerSource),
                     bits};
      decode_.dispatchItems(cmd, received, 64, d);
      vk::computeToTransferBarrier(cmd);
    } else {
      transferBarrier(cmd);
    }
    copyBuffer(cmd, recvCounts_, 0, recvOffsets_, 0, uint64_t(received) * 4);
    vk::transferToComputeBarrier(cmd);
    scan_.record(cmd, recvOffsets_.address(), received);
    vk::computeToTransferBarrier(cmd);
    copyBoundaries(cmd, recvOffsets_, received, recvBoundaries_, recvIndices_);
    hostReadBarrier(cmd);
  });
  recvTotal_ = scan_.downloadTotal("the list lengths received");
  readBoundaries(recvBoundaries_, received, recvTotal_, recvIndices_, recvBegin_);
  stats.fragmentsComposited = recvTotal_;
}

// Step 3: the fragments themselves.
void DeepExchange::exchangeFragments(CompositeStats& stats) {
  Transfer t = planFragmentExchange(sendBegin_, recvBegin_, fragmentBytes_);
  grow(recvFragmentStage_, recvTotal_ * fragmentBytes_, MemoryUse::Upload,
       "fragment receive stage");
  grow(recvFragments_, recvTotal_ * fragmentBytes_, MemoryUse::Device, "received fragments");
  comm_.alltoallv(sendFragmentStage_.mapped(), t.sendBytes, t.sendOffsets,
                  recvFragmentStage_.mapped(), t.recvBytes, t.recvOffsets);
  stats.fragmentBytesSent = t.sentToOthers(rank_);
  stats.bytesSent = stats.countBytesSent + stats.fragmentBytesSent;
}

// Step 4.
void DeepExchange::compositeOwned() {
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    previousWorkBarrier(cmd);
    hostWriteBarrier(cmd);
    copyBuffer(cmd, recvFragmentStage_, 0, recvFragments_, 0, recvTotal_ * fragmentBytes_);
    vk::transferToComputeBarrier(cmd);
    DcDeepPush p{recvFragments_.address(),
                 recvCounts_.address(),
                 recvOffsets_.address(),
                 ownedImage_.address(),
                 owned_,
                 uint32_t(ranks_)};
    composite_.dispatchItems(cmd, owned_, 64, p);
    hostReadBarrier(cmd);
  });
}

const vk::Buffer& DeepExchange::positionCounts(const ListsView& lists) const {
  return interleaved() ? sendCounts_ : *lists.counts;
}

// Step 5: rank 0 receives every rank's positions straight into the image (Ranges), or into
// position order and then puts each pixel in its place (Interleaved).
void DeepExchange::gather(std::vector<glm::vec4>& image) {
  std::vector<uint64_t> bytes, offsets;
  if (rank_ == 0) {
    image.resize(pixels_);
    if (interleaved()) gathered_.resize(pixels_);
    for (int r = 0; r < ranks_; ++r) {
      bytes.push_back(ranges_.count(r) * sizeof(glm::vec4));
      offsets.push_back(ranges_.begin(r) * sizeof(glm::vec4));
    }
  }
  glm::vec4* target = rank_ == 0 && interleaved() ? gathered_.data() : image.data();
  comm_.gatherv(ownedImage_.mapped(), uint64_t(owned_) * sizeof(glm::vec4), target, bytes, offsets,
                0);
  if (rank_ != 0 || !interleaved()) return;
  // Rank r's j-th position is pixel j R + r (PixelRanges::pixelAt): row j of R pixels takes
  // the j-th entry of every rank, so the image is written in order from R read streams.
  const uint64_t R = uint64_t(ranks_);
  std::vector<const glm::vec4*> from(static_cast<size_t>(ranks_));
  for (int r = 0; r < ranks_; ++r) from[size_t(r)] = gathered_.data() + ranges_.begin(r);
  for (uint64_t j = 0, p = 0; p < pixels_; ++j)
    for (size_t r = 0; r < R && p < pixels_; ++r, ++p) image[p] = from[r][j];
}

}  // namespace sm::comp
