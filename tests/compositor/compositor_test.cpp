// The compositor on in-process ranks (1 to 4 threads, one Vulkan context each, LocalCommunicator)
// against the serial reference and the host model of the device interface. Every rank's context
// runs the validation layer and must report nothing.
#include <atomic>

#include <gtest/gtest.h>

#include "compositor/local_communicator.h"
#include "compositor_cases.h"
#include "vk/context.h"

namespace sm::comp::test {
namespace {

using Case = void (*)(Communicator*, const vk::Context&);

vk::ContextOptions computeOnly(bool forceStaging = false) {
  vk::ContextOptions o;
  o.requireRayQuery = false;
  o.forceStaging = forceStaging;
  return o;
}

void onLocalRanks(int ranks, Case body, bool forceStaging = false) {
  runLocalRanks(ranks, [&](Communicator& comm) {
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
    runLocalRanks(3, [&](Communicator& comm) {
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
  } catch (const CommAborted&) {
    FAIL() << "the original error, not the others' CommAborted, must reach the caller";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "injected failure on rank 1");
  }
  EXPECT_EQ(completed, 0) << "no rank can finish a frame without rank 1";
}

}  // namespace
}  // namespace sm::comp::test
