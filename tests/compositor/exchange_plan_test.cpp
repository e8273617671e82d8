// Host-side logic without a device: pixel ownership, counter widths at their boundaries, the byte
// accounting of both exchanges, MPI chunk planning for sizes beyond `int`, and the replay.
#include <gtest/gtest.h>

#include <algorithm>
#include <climits>
#include <numeric>

#include "comm/communicator.h"
#include "compositor/count_codec.h"
#include "compositor/exchange_plan.h"
#include "compositor/tools/replay.h"

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
    PixelRanges r(pixels, ranks, PixelOwnership::Ranges);
    EXPECT_EQ(r.begin(0), 0u);
    EXPECT_EQ(r.end(ranks - 1), pixels);
    for (int d = 0; d < ranks; ++d) {
      EXPECT_LE(r.begin(d), r.end(d));
      EXPECT_LE(r.count(d), pixels / uint64_t(ranks) + 1) << "balanced";
      for (uint64_t p = r.begin(d); p < r.end(d); ++p) ASSERT_EQ(r.owner(p), d) << p;
    }
  }
  EXPECT_THROW(PixelRanges(10, 0, PixelOwnership::Ranges), std::invalid_argument);
  EXPECT_THROW(PixelRanges(10, 2, PixelOwnership::Ranges).owner(10), std::out_of_range);
}

// Interleaved: rank d's positions stand for the pixels p = d (mod R) in increasing order, every
// pixel at exactly one position, and the position's owner is the pixel's owner.
TEST(CompositorPixelRanges, InterleavedPositionsAreAPermutationDealingPixelsRoundRobin) {
  for (auto [pixels, ranks] :
       {std::pair<uint64_t, int>{1, 4}, {3, 4}, {4, 4}, {221, 3}, {1000, 7}, {65536, 7}}) {
    PixelRanges r(pixels, ranks, PixelOwnership::Interleaved);
    EXPECT_EQ(r.begin(0), 0u);
    EXPECT_EQ(r.end(ranks - 1), pixels);
    std::vector<int> seen(pixels, 0);
    for (int d = 0; d < ranks; ++d) {
      // The first P mod R ranks hold one pixel more.
      EXPECT_EQ(r.count(d), pixels / uint64_t(ranks) + (uint64_t(d) < pixels % uint64_t(ranks)));
      for (uint64_t q = r.begin(d); q < r.end(d); ++q) {
        ASSERT_EQ(r.owner(q), d) << q;
        const uint64_t p = r.pixelAt(q);
        ASSERT_EQ(p, (q - r.begin(d)) * uint64_t(ranks) + uint64_t(d)) << q;
        ASSERT_LT(p, pixels);
        ASSERT_EQ(r.ownerOfPixel(p), d) << p;
        ASSERT_EQ(r.positionOf(p), q) << p;
        ++seen[p];
      }
    }
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), int64_t(pixels)) << "a permutation";
  }
  PixelRanges ranges(221, 3, PixelOwnership::Ranges);
  for (uint64_t q = 0; q < 221; ++q) {
    EXPECT_EQ(ranges.pixelAt(q), q);
    EXPECT_EQ(ranges.positionOf(q), q);
    EXPECT_EQ(ranges.ownerOfPixel(q), ranges.owner(q));
  }
  // The largest image the compositor takes: positions and pixels round-trip at both ends.
  for (int ranks : {2, 3, 7, 2999}) {
    PixelRanges big(0xFFFFFFFFull, ranks, PixelOwnership::Interleaved);
    const uint64_t R = uint64_t(ranks), last = big.pixels() - 1;
    for (uint64_t p : std::vector<uint64_t>{0, 1, R, last - R, last - 1, last}) {
      const uint64_t q = big.positionOf(p);
      ASSERT_LT(q, big.pixels()) << p;
      EXPECT_EQ(big.pixelAt(q), p) << p << " on " << ranks << " ranks";
      EXPECT_EQ(big.owner(q), big.ownerOfPixel(p)) << p;
    }
  }
  EXPECT_THROW(PixelRanges(10, 3, PixelOwnership::Interleaved).pixelAt(10), std::out_of_range);
  EXPECT_THROW(PixelRanges(10, 3, PixelOwnership::Interleaved).ownerOfPixel(10), std::out_of_range);
  EXPECT_THROW(PixelRanges(10, 3, PixelOwnership::Interleaved).positionOf(10), std::out_of_range);
  EXPECT_EQ(parseOwnership("interleaved"), PixelOwnership::Interleaved);
  EXPECT_EQ(parseOwnership("ranges"), PixelOwnership::Ranges);
  EXPECT_STREQ(ownershipName(PixelOwnership::Interleaved), "interleaved");
  EXPECT_THROW(parseOwnership("tiles"), std::invalid_argument);
}

TEST(CompositorCountExchange, SendsOnlyTheBytesThatHoldCountersFromWordAlignedShares) {
  PixelRanges r(221, 3, PixelOwnership::Ranges);  // 73, 74, 74 pixels
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
      PixelRanges r(pixels, ranks, PixelOwnership::Ranges);
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

TEST(CompositorReplay, PredictsBytesAndLoadFromCounts) {
  // 2 ranks, 4 pixels: rank 0 owns pixels 0-1, rank 1 owns 2-3.
  std::vector<std::vector<uint32_t>> counts = {{1, 0, 2, 3}, {0, 4, 0, 1}};
  ReplayResult r = replayExchange(4, 2, Encoding::Rgba8, 0, PixelOwnership::Ranges,
                                  [&](int rank, std::vector<uint32_t>& c) { c = counts[rank]; });
  EXPECT_EQ(r.counterBits, 4u);  // longest list 4
  EXPECT_EQ(r.ranks[0].fragments, 6u);
  EXPECT_EQ(r.ranks[0].nonEmptyPixels, 3u);
  EXPECT_EQ(r.ranks[0].fragmentBytesSent, 5u * 8);  // pixels 2-3 go to rank 1
  EXPECT_EQ(r.ranks[1].fragmentBytesSent, 4u * 8);
  EXPECT_EQ(r.ranks[0].fragmentsComposited, 5u);
  EXPECT_EQ(r.ranks[1].fragmentsComposited, 6u);
  EXPECT_EQ(r.ranks[0].countBytesSent, 8u + 1u);  // a header, then two 4-bit counters
  EXPECT_EQ(r.ranks[1].fragmentBytesReceived, 5u * 8);
  EXPECT_DOUBLE_EQ(r.imbalance(&ReplayRank::fragmentsComposited), 6.0 / 5.5);

  // Interleaved, the same counts: rank 0 owns pixels 0 and 2, rank 1 pixels 1 and 3.
  ReplayResult i = replayExchange(4, 2, Encoding::Rgba8, 0, PixelOwnership::Interleaved,
                                  [&](int rank, std::vector<uint32_t>& c) { c = counts[rank]; });
  EXPECT_EQ(i.ranks[0].fragmentBytesSent, 3u * 8);  // pixel 3 goes to rank 1
  EXPECT_EQ(i.ranks[1].fragmentBytesSent, 0u);      // pixels 0 and 2 are empty on rank 1
  EXPECT_EQ(i.ranks[0].fragmentsComposited, 3u);
  EXPECT_EQ(i.ranks[1].fragmentsComposited, 8u);
  EXPECT_EQ(i.ranks[0].countBytesSent, 8u + 1u);
}

// dcDivide's multiply-and-shift equals the division for every divisor a rank count can be and
// the numerators where rounding would show first: around multiples of the divisor, and the top of
// the 32-bit range.
TEST(CompositorDivision, MagicNumbersDivideExactly) {
  std::vector<uint32_t> divisors;
  for (uint32_t d = 2; d < 3000; ++d) divisors.push_back(d);
  for (uint32_t d : {4095u, 4096u, 4097u, 65535u, 65536u, 65537u, 1000003u, 0x7FFFFFFFu,
                     0x80000000u, 0x80000001u, 0xFFFFFFFEu, 0xFFFFFFFFu})
    divisors.push_back(d);
  for (uint32_t d : divisors) {
    const DcDivisor m = dcDivisionMagic(d);
    auto check = [&](uint64_t n) {
      if (n > 0xFFFFFFFFull) return;
      ASSERT_EQ(dcDivide(uint32_t(n), m), uint32_t(n / d)) << n << " / " << d;
    };
    const uint64_t top = 0xFFFFFFFFull / d;
    for (uint64_t k : std::vector<uint64_t>{0, 1, 2, 1000, top - 1, top})
      for (uint64_t n : {k * d, k * d + 1, k * d + d - 1}) check(n);
    for (uint64_t n = 0xFFFFFFFFull - 300; n <= 0xFFFFFFFFull; ++n) check(n);
  }
  EXPECT_THROW(dcDivisionMagic(1), std::invalid_argument);
  EXPECT_THROW(dcDivisionMagic(0), std::invalid_argument);
}

TEST(CompositorCountCodec, ZeroRunsRoundTripAndNeverLoseAWord) {
  const std::vector<std::vector<uint32_t>> cases = {{},
                                                    {0},
                                                    {7},
                                                    {0, 0, 0, 5},
                                                    {5, 0, 0, 0},
                                                    {5, 0, 6, 0},
                                                    {0, 5, 0, 0, 6, 7, 0, 0, 0, 8},
                                                    std::vector<uint32_t>(1000, 0),
                                                    std::vector<uint32_t>(1000, 9)};
  for (const auto& words : cases) {
    std::vector<uint32_t> code;
    appendZeroRuns(words, code);
    std::vector<uint32_t> back(words.size(), 0xDEADBEEFu);
    expandZeroRuns(code, back);
    EXPECT_EQ(back, words) << words.size() << " words";
    EXPECT_EQ(zeroRunWords(words), code.size()) << words.size() << " words";
    // Never longer than the words plus one record per literal run.
    EXPECT_LE(code.size(), words.size() + 2 * (words.size() / 2 + 1));
  }
  std::vector<uint32_t> code;
  appendZeroRuns(std::vector<uint32_t>(1000, 0), code);
  EXPECT_EQ(code, (std::vector<uint32_t>{1000, 0})) << "an empty share is one record";
  code.clear();
  appendZeroRuns(std::vector<uint32_t>{7, 0}, code);
  EXPECT_EQ(code, (std::vector<uint32_t>{0, 2, 7, 0})) << "a last single zero is a literal";
  // A code for the wrong number of words is refused, whichever way it is wrong.
  std::vector<uint32_t> four(4);
  EXPECT_THROW(expandZeroRuns(std::vector<uint32_t>{3, 0}, four), comm::CommError);
  EXPECT_THROW(expandZeroRuns(std::vector<uint32_t>{5, 0}, four), comm::CommError);
  EXPECT_THROW(expandZeroRuns(std::vector<uint32_t>{2, 2, 1}, four), comm::CommError);
  EXPECT_THROW(expandZeroRuns(std::vector<uint32_t>{4, 0, 9}, four), comm::CommError);
  // Packing is encode_counts.comp's: counter i at bits (i % per word) * bits of word i / per word.
  std::vector<uint32_t> packed;
  packCounterWords(std::vector<uint32_t>{1, 2, 3}, 4, packed);
  EXPECT_EQ(packed, (std::vector<uint32_t>{0x321u}));
  packCounterWords(std::vector<uint32_t>(17, 1), 2, packed);
  EXPECT_EQ(packed, (std::vector<uint32_t>{0x55555555u, 0x1u}));
  packCounterWords(std::vector<uint32_t>{300, 7}, 32, packed);
  EXPECT_EQ(packed, (std::vector<uint32_t>{300, 7}));
  // Five zero words code as one record of two words.
  const std::vector<uint32_t> zeros(5, 0u);
  EXPECT_EQ(choosePayload(zeros, 19).bytes, 8u);
  EXPECT_TRUE(choosePayload(zeros, 19).zeroRuns);
  EXPECT_FALSE(choosePayload(zeros, 7).zeroRuns) << "dense when the code is not smaller";
  EXPECT_EQ(choosePayload(zeros, 7).bytes, 7u);
}

// A rank whose data covers a few pixels sends each destination a header and one short record
// instead of a counter for every pixel the destination owns.
TEST(CompositorReplay, CountsOfTheWrongSizeAreRefused) {
  EXPECT_THROW(replayExchange(16, 2, Encoding::Float, 0, PixelOwnership::Interleaved,
                              [](int, std::vector<uint32_t>& c) { c.resize(8); }),
               std::invalid_argument);
}

TEST(CompositorReplay, SparseCoverageSendsZeroRunsInsteadOfEveryCounter) {
  const uint64_t pixels = 256 * 256;
  auto few = [&](int rank, std::vector<uint32_t>& c) {
    for (uint64_t p = 0; p < c.size(); ++p) c[p] = p % 997 == uint64_t(rank) ? 3u : 0u;
  };
  for (PixelOwnership own : {PixelOwnership::Interleaved, PixelOwnership::Ranges}) {
    ReplayResult r = replayExchange(pixels, 8, Encoding::Float, 0, own, few);
    ASSERT_EQ(r.counterBits, 2u);
    const PixelRanges ranges(pixels, 8, own);
    for (int s = 0; s < 8; ++s) {
      const uint64_t dense = planCountExchange(ranges, s, 2).transfer.sentToOthers(s);
      EXPECT_LT(r.ranks[size_t(s)].countBytesSent * 4, dense)
          << ownershipName(own) << " rank " << s;
    }
  }
}

// The case interleaving exists for: the data covers one band of the image (a view off to one
// side), so contiguous ranges leave most ranks with nothing to composite.
TEST(CompositorReplay, InterleavedOwnershipBalancesAViewCoveringPartOfTheImage) {
  const uint64_t width = 64, height = 48;
  auto covered = [&](int rank, std::vector<uint32_t>& c) {
    for (uint64_t p = 0; p < c.size(); ++p)
      c[p] = p / width < height / 4 ? 1u + uint32_t(rank) : 0u;
  };
  ReplayResult ranges =
      replayExchange(width * height, 4, Encoding::Float, 0, PixelOwnership::Ranges, covered);
  ReplayResult inter =
      replayExchange(width * height, 4, Encoding::Float, 0, PixelOwnership::Interleaved, covered);
  EXPECT_DOUBLE_EQ(ranges.imbalance(&ReplayRank::fragmentsComposited), 4.0) << "rank 0 owns it all";
  EXPECT_DOUBLE_EQ(inter.imbalance(&ReplayRank::fragmentsComposited), 1.0);
  uint64_t a = 0, b = 0;
  for (int r = 0; r < 4; ++r) {
    a += ranges.ranks[size_t(r)].fragmentsComposited;
    b += inter.ranks[size_t(r)].fragmentsComposited;
  }
  EXPECT_EQ(a, b) << "the same fragments, composited elsewhere";
}

}  // namespace
}  // namespace sm::comp
