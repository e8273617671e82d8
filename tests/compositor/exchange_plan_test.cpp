// Host-side logic without a device: pixel ownership, counter widths at their boundaries, the byte
// accounting of both exchanges, MPI chunk planning for sizes beyond `int`, and the replay.
#include <gtest/gtest.h>

#include <climits>
#include <numeric>

#include "compositor/exchange_plan.h"
#include "compositor/mpi/mpi_communicator.h"
#include "compositor/replay.h"

namespace sm::comp {
namespace {

TEST(CompositorCounterBits, ChosenAtThe2_4_8_32BitBoundaries) {
  EXPECT_EQ(counterBits(0), 2u);
  EXPECT_EQ(counterBits(3), 2u);
  EXPECT_EQ(counterBits(4), 4u);
  EXPECT_EQ(counterBits(15), 4u);
  EXPECT_EQ(counterBits(16), 8u);
  EXPECT_EQ(counterBits(255), 8u);
  EXPECT_EQ(counterBits(256), 32u);
  EXPECT_EQ(counterBits(uint64_t(1) << 40), 32u);
}

TEST(CompositorCounterBits, ForcedWidthMustBeAnEncodingThatHoldsTheLongestList) {
  EXPECT_EQ(chooseCounterBits(3, 8), 8u);
  EXPECT_EQ(chooseCounterBits(255, 8), 8u);
  EXPECT_EQ(chooseCounterBits(100000, 32), 32u);
  EXPECT_THROW(chooseCounterBits(4, 2), std::invalid_argument);
  EXPECT_THROW(chooseCounterBits(256, 8), std::invalid_argument);
  EXPECT_THROW(chooseCounterBits(1, 16), std::invalid_argument);
}

TEST(CompositorPixelRanges, EveryPixelHasExactlyOneOwnerInContiguousRanges) {
  for (auto [pixels, ranks] : {std::pair<uint64_t, int>{1, 4}, {3, 4}, {221, 3}, {65536, 7}}) {
    PixelRanges r(pixels, ranks);
    EXPECT_EQ(r.begin(0), 0u);
    EXPECT_EQ(r.end(ranks - 1), pixels);
    for (int d = 0; d < ranks; ++d) {
      EXPECT_LE(r.begin(d), r.end(d));
      EXPECT_LE(r.count(d), pixels / uint64_t(ranks) + 1) << "balanced";
      for (uint64_t p = r.begin(d); p < r.end(d); ++p) ASSERT_EQ(r.owner(p), d) << p;
    }
  }
  EXPECT_THROW(PixelRanges(10, 0), std::invalid_argument);
  EXPECT_THROW(PixelRanges(10, 2).owner(10), std::out_of_range);
}

TEST(CompositorCountExchange, SendsOnlyTheBytesThatHoldCountersFromWordAlignedShares) {
  PixelRanges r(221, 3);  // 73, 74, 74 pixels
  CountExchange c = planCountExchange(r, 1, 2);
  EXPECT_EQ(c.sendWordBegin, (std::vector<uint64_t>{0, 5, 10, 15}));  // 16 counters per word
  EXPECT_EQ(c.transfer.sendBytes, (std::vector<uint64_t>{19, 19, 19}));
  EXPECT_EQ(c.transfer.sendOffsets, (std::vector<uint64_t>{0, 20, 40}));
  EXPECT_EQ(c.wordsPerSource, 5u);
  EXPECT_EQ(c.transfer.recvBytes, (std::vector<uint64_t>{19, 19, 19}));
  EXPECT_EQ(c.transfer.recvOffsets, (std::vector<uint64_t>{0, 20, 40}));
  EXPECT_EQ(c.transfer.sentToOthers(1), 38u);
  CountExchange full = planCountExchange(r, 0, 32);
  EXPECT_EQ(full.transfer.sendOffsets, (std::vector<uint64_t>{0, 73 * 4, 147 * 4}));
  EXPECT_EQ(full.transfer.recvBytes, (std::vector<uint64_t>{73 * 4, 73 * 4, 73 * 4}));
}

TEST(CompositorCountExchange, WhatEachRankSendsIsWhatItsPeerExpects) {
  for (uint32_t bits : {2u, 4u, 8u, 32u}) {
    for (auto [pixels, ranks] : {std::pair<uint64_t, int>{1, 4}, {17 * 13, 4}, {1000, 7}}) {
      PixelRanges r(pixels, ranks);
      std::vector<CountExchange> plans;
      for (int s = 0; s < ranks; ++s) plans.push_back(planCountExchange(r, s, bits));
      for (int s = 0; s < ranks; ++s)
        for (int d = 0; d < ranks; ++d)
          EXPECT_EQ(plans[size_t(s)].transfer.sendBytes[size_t(d)],
                    plans[size_t(d)].transfer.recvBytes[size_t(s)]);
    }
  }
}

TEST(CompositorFragmentExchange, BoundariesOfTheScansBecomeSizesAndOffsets) {
  std::vector<uint64_t> send = {0, 4, 4, 10}, recv = {0, 3, 5, 9};
  Transfer t = planFragmentExchange(send, recv, 20);
  EXPECT_EQ(t.sendBytes, (std::vector<uint64_t>{80, 0, 120}));
  EXPECT_EQ(t.sendOffsets, (std::vector<uint64_t>{0, 80, 80}));
  EXPECT_EQ(t.recvBytes, (std::vector<uint64_t>{60, 40, 80}));
  EXPECT_EQ(t.recvOffsets, (std::vector<uint64_t>{0, 60, 100}));
  EXPECT_EQ(t.sentToOthers(2), 80u);
  std::vector<uint64_t> bad = {0, 5, 4, 10};
  EXPECT_THROW(planFragmentExchange(bad, recv, 20), std::logic_error);
}

TEST(CompositorMpiChunks, TransfersBeyondIntSplitIntoPiecesThatFit) {
  const uint64_t maxBytes = uint64_t(1) << 30;
  ChunkPlan p = planChunks(5 * maxBytes + 7, maxBytes);
  EXPECT_EQ(p.chunks, 5u);
  EXPECT_EQ(p.tail, 7u);
  p = planChunks(uint64_t(INT_MAX) + 1, uint64_t(INT_MAX));
  EXPECT_EQ(p.chunks, 1u);
  EXPECT_EQ(p.tail, 1u);
  p = planChunks(100, 7);
  EXPECT_EQ(p.chunks * 7 + p.tail, 100u);
  EXPECT_LT(p.tail, 7u);
  EXPECT_THROW(planChunks(1, 0), CommError);
}

TEST(CompositorReplay, PredictsBytesAndLoadFromCounts) {
  // 2 ranks, 4 pixels: rank 0 owns pixels 0-1, rank 1 owns 2-3.
  std::vector<std::vector<uint32_t>> counts = {{1, 0, 2, 3}, {0, 4, 0, 1}};
  ReplayResult r = replayExchange(4, 2, Encoding::Rgba8, 0,
                                  [&](int rank, std::vector<uint32_t>& c) { c = counts[rank]; });
  EXPECT_EQ(r.counterBits, 4u);  // longest list 4
  EXPECT_EQ(r.ranks[0].fragments, 6u);
  EXPECT_EQ(r.ranks[0].nonEmptyPixels, 3u);
  EXPECT_EQ(r.ranks[0].fragmentBytesSent, 5u * 8);  // pixels 2-3 go to rank 1
  EXPECT_EQ(r.ranks[1].fragmentBytesSent, 4u * 8);
  EXPECT_EQ(r.ranks[0].fragmentsComposited, 5u);
  EXPECT_EQ(r.ranks[1].fragmentsComposited, 6u);
  EXPECT_EQ(r.ranks[0].countBytesSent, 1u);  // two 4-bit counters
  EXPECT_EQ(r.ranks[1].fragmentBytesReceived, 5u * 8);
  EXPECT_DOUBLE_EQ(r.imbalance(&ReplayRank::fragmentsComposited), 6.0 / 5.5);
}

}  // namespace
}  // namespace sm::comp
