// The compositor on in-process ranks (1 to 4 threads, one Vulkan context each, LocalCommunicator)
// against the serial reference and the host model of the device interface. Every rank's context
// runs the validation layer and must report nothing.
#include <algorithm>
#include <atomic>
#include <random>

#include <gtest/gtest.h>

#include "comm/local_communicator.h"
#include "compositor/device_util.h"
#include "compositor/list_statistics.h"
#include "compositor/prefix_sum.h"
#include "compositor_cases.h"
#include "vk/context.h"

namespace sm::comp::test {
namespace {

using Case = void (*)(comm::Communicator*, const vk::Context&);

vk::ContextOptions computeOnly(bool forceStaging = false) {
  vk::ContextOptions o;
  o.rayTracing = false;
  o.forceStaging = forceStaging;
  return o;
}

void onLocalRanks(int ranks, Case body, bool forceStaging = false) {
  comm::runLocalRanks(ranks, [&](comm::Communicator& comm) {
    vk::Context ctx(computeOnly(forceStaging));
    body(&comm, ctx);
    EXPECT_EQ(ctx.validationErrors(), 0u) << "rank " << comm.rank();
    EXPECT_EQ(ctx.validationWarnings(), 0u) << "rank " << comm.rank();
  });
}

class CompositorInProcess : public ::testing::TestWithParam<int> {};

TEST_P(CompositorInProcess, SmallImagesMatchSerialReference) {
  onLocalRanks(GetParam(), checkSmallImages);
}
TEST_P(CompositorInProcess, LargeImageMatchesSerialReference) {
  onLocalRanks(GetParam(), checkLargeImage);
}
TEST_P(CompositorInProcess, FixedListsDropAndMergeAsTheHostModel) {
  onLocalRanks(GetParam(), checkFixedLists);
}
TEST_P(CompositorInProcess, CounterWidthFollowsTheLongestListOfAnyRank) {
  onLocalRanks(GetParam(), checkCounterBoundaries);
}
TEST_P(CompositorInProcess, SingleFragmentDiffersWhereRanksInterleave) {
  onLocalRanks(GetParam(), checkSingleFragment);
}
TEST_P(CompositorInProcess, StatisticsMatchTheReplay) {
  onLocalRanks(GetParam(), checkStatistics);
}
TEST_P(CompositorInProcess, SteadyFramesAllocateNothing) {
  onLocalRanks(GetParam(), checkBuffersOnlyGrow);
}
TEST_P(CompositorInProcess, ListsBeyondRegistersMergeInMemory) {
  onLocalRanks(GetParam(), checkMemoryMerge);
}

INSTANTIATE_TEST_SUITE_P(Ranks, CompositorInProcess, ::testing::Values(1, 2, 3, 4),
                         [](const auto& info) { return std::to_string(info.param) + "ranks"; });

// One rank composites every pixel of the image (list statistics, compositing); two exchange and
// decode counts for every pixel. Not run at every rank count: the image is 4 M pixels.
TEST(CompositorLargeDispatch, ImagesBeyondOneRowOfWorkgroups) {
  onLocalRanks(1, checkBeyondOneDispatchRow);
  onLocalRanks(2, checkBeyondOneDispatchRow);
}

// Scans of n equal values: offsets and total exact up to kMaxListIndex (2^31 - 1); beyond, the
// total is refused (past 2^32 it has wrapped). One level (2047 and 4097 values of 2^20: below the
// limit, and past 2^32) and three (2 million values: below it, and between 2^31 and 2^32).
TEST(PrefixSum, TotalsBeyond32BitsAreRefused) {
  vk::Context ctx(computeOnly());
  PrefixSum scan(ctx);
  auto run = [&](uint32_t n, uint32_t value) {
    std::vector<uint32_t> v(n, value);
    vk::Buffer b = vk::makeBuffer<uint32_t>(ctx, v, "scanned values");
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      scan.record(cmd, b.address(), n);
      hostReadBarrier(cmd);
    });
    return b.download<uint32_t>();
  };
  for (auto [n, value] : {std::pair{2047u, 1u << 20}, std::pair{2000000u, 1073u}}) {
    std::vector<uint32_t> offsets = run(n, value);
    EXPECT_EQ(scan.downloadTotal("values"), uint64_t(n) * value) << n;
    size_t wrong = 0;
    for (uint32_t i = 0; i < n; ++i) wrong += offsets[i] != uint64_t(i) * value;
    EXPECT_EQ(wrong, 0u) << n;
  }
  // The last: each 2^20 values of a level-2 block total exactly 2^32, which wrapped to 0 below the
  // top level (and the total read 4M); block totals that would wrap saturate instead.
  for (auto [n, value] : {std::pair{4097u, 1u << 20}, std::pair{2000000u, 1100u},
                          std::pair{(1u << 20) + 1024u, 4096u}}) {
    run(n, value);
    EXPECT_THROW(scan.downloadTotal("values"), std::overflow_error) << n;
  }
  // A block holding one value of 4M or more (the 64-bit path) still scans exactly.
  {
    const uint32_t n = 3000;
    std::vector<uint32_t> v(n, 1u);
    v[5] = 3u << 30;
    vk::Buffer b = vk::makeBuffer<uint32_t>(ctx, v, "scanned values");
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      scan.record(cmd, b.address(), n);
      hostReadBarrier(cmd);
    });
    const std::vector<uint32_t> offsets = b.download<uint32_t>();
    uint64_t expect = 0;
    size_t wrong = 0;
    for (uint32_t i = 0; i < n; ++i) {
      wrong += offsets[i] != expect;
      expect += v[i];
    }
    EXPECT_EQ(wrong, 0u);
    EXPECT_THROW(scan.downloadTotal("values"), std::overflow_error);  // 3 * 2^30 + 2999 > 2^31 - 1
  }
  EXPECT_EQ(ctx.validationErrors(), 0u);
}

// Fixed-length lists whose slots pass kMaxListIndex are refused, naming --k, when the compositor
// is made and before any buffer is.
TEST(DeepCompositorLimits, FixedListSlotsBeyond31BitsAreRefused) {
  vk::Context ctx(computeOnly());
  CompositorOptions o;
  o.mode = ListMode::FixedMerge;
  o.fixedK = 8;
  try {
    DeepCompositor c(ctx, nullptr, 16384, 16385, o);  // 2 147 614 720 slots
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("(--k)"), std::string::npos) << e.what();
  }
  EXPECT_EQ(ctx.validationErrors(), 0u);
}

// Devices whose memory the host cannot map: every transfer goes through staging copies.
TEST(CompositorStaging, ExchangeWithoutMappedDeviceMemory) {
  onLocalRanks(3, checkSmallImages, true);
}

// The renderer's one-rank use: no communicator at all.
TEST(CompositorOneRank, WithoutCommunicator) {
  vk::Context ctx(computeOnly());
  checkSmallImages(nullptr, ctx);
  checkFixedLists(nullptr, ctx);
  EXPECT_EQ(ctx.validationErrors(), 0u);
  EXPECT_EQ(ctx.validationWarnings(), 0u);
}

// An error on one rank in the middle of a frame ends the others' collectives with its message
// instead of leaving them waiting.
TEST(CompositorErrors, FailureOnOneRankEndsAllRanksWithItsMessage) {
  std::atomic<int> completed = 0;
  try {
    comm::runLocalRanks(3, [&](comm::Communicator& comm) {
      vk::Context ctx(computeOnly());
      WorldSpec s;
      s.ranks = 3;
      World w = makeWorld(s);
      RankRig rig(&comm, ctx, s.width, s.height, {});
      rig.run(w);  // a good frame first
      if (comm.rank() == 1) throw std::runtime_error("injected failure on rank 1");
      rig.run(w);
      ++completed;
    });
    FAIL() << "expected the injected error";
  } catch (const comm::CommAborted&) {
    FAIL() << "the original error, not the others' comm::CommAborted, must reach the caller";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "injected failure on rank 1");
  }
  EXPECT_EQ(completed, 0) << "no rank can finish a frame without rank 1";
}

// The list statistics over many workgroups (each sums 4096 counts), the last one partial, with the
// longest list in it: every total must match the host's.
TEST(ListStatistics, ManyWorkgroupsMatchTheHost) {
  vk::Context ctx(computeOnly());
  for (uint32_t pixels : {1u, 4095u, 4097u, 70001u}) {
    std::mt19937 rng(pixels);
    std::vector<uint32_t> counts(pixels);
    for (uint32_t& c : counts) c = rng() % 3 == 0 ? 0u : rng() % 6;
    counts[pixels - 1] = 77;  // in the last (partial) workgroup
    if (pixels > 100) counts[pixels / 2] = 0;
    vk::Buffer buf(ctx, uint64_t(pixels) * 4, vk::kStorageUsage, vk::MemoryUse::Device,
                   "test: counts");
    buf.upload(counts.data(), uint64_t(pixels) * 4);
    ListStatistics stats(ctx);
    ctx.submitAndWait([&](VkCommandBuffer cmd) { stats.record(cmd, buf.address(), pixels); });
    ListTotals t = stats.read();
    uint64_t fragments = 0, nonEmpty = 0;
    for (uint32_t c : counts) {
      fragments += c;
      nonEmpty += c > 0 ? 1 : 0;
    }
    EXPECT_EQ(t.longest, *std::max_element(counts.begin(), counts.end())) << pixels;
    EXPECT_EQ(t.nonEmptyPixels, nonEmpty) << pixels;
    EXPECT_EQ(t.fragments, fragments) << pixels;
  }
  EXPECT_EQ(ctx.validationErrors(), 0u);
}

}  // namespace
}  // namespace sm::comp::test
