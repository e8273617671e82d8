// The compositor under mpiexec (1 to 4 processes, see CMakeLists.txt): the same cases as the
// in-process ranks over MPI, with transfers chunked far below `int` to exercise the overflow
// protection, and an error on one rank that must end all of them (run by mpi_abort_check.sh).
#include <gtest/gtest.h>

#include "compositor_cases.h"
#include "mpi_world.h"

namespace sm::comp::test {
namespace {

class CompositorMpi : public ::testing::Test {
 protected:
  void SetUp() override { splitBefore_ = mpiWorld().splitTransfers(); }
  void TearDown() override {
    if (!chunked_) {
      EXPECT_EQ(mpiWorld().splitTransfers(), splitBefore_) << "small frames fit one MPI_Alltoallv";
    }
    EXPECT_EQ(mpiContext().validationErrors(), 0u) << "rank " << mpiWorld().rank();
    EXPECT_EQ(mpiContext().validationWarnings(), 0u) << "rank " << mpiWorld().rank();
  }
  void run(void (*body)(comm::Communicator*, const vk::Context&)) {
    body(&mpiWorld(), mpiContext());
  }
  uint64_t splitBefore_ = 0;
  bool chunked_ = false;
};

TEST_F(CompositorMpi, SmallImagesMatchSerialReference) {
  run(checkSmallImages);
}
TEST_F(CompositorMpi, LargeImageMatchesSerialReference) {
  run(checkLargeImage);
}
TEST_F(CompositorMpi, FixedListsDropAndMergeAsTheHostModel) {
  run(checkFixedLists);
}
TEST_F(CompositorMpi, CounterWidthFollowsTheLongestListOfAnyRank) {
  run(checkCounterBoundaries);
}
TEST_F(CompositorMpi, SingleFragmentDiffersWhereRanksInterleave) {
  run(checkSingleFragment);
}
TEST_F(CompositorMpi, StatisticsMatchTheReplay) {
  run(checkStatistics);
}
TEST_F(CompositorMpi, SteadyFramesAllocateNothing) {
  run(checkBuffersOnlyGrow);
}
TEST_F(CompositorMpi, ListsBeyondRegistersMergeInMemory) {
  run(checkMemoryMerge);
}

// With at most 7 bytes per MPI message or datatype block, every alltoallv goes through
// MPI_Alltoallw with chunked derived datatypes and every gather through several receives per rank:
// the path that transfers beyond INT_MAX bytes take, at sizes a test can afford.
TEST_F(CompositorMpi, TransfersChunkedBelowIntLimitsGiveTheSameImages) {
  chunked_ = true;
  mpiWorld().setMaxMessageBytes(7);
  run(checkSmallImages);
  run(checkStatistics);
  run(checkSingleFragment);
  mpiWorld().setMaxMessageBytes(uint64_t(1) << 30);
  if (mpiWorld().size() > 1) {
    EXPECT_GT(mpiWorld().splitTransfers(), splitBefore_) << "the chunked path must have run";
  }
}

// MPI_ERRORS_RETURN: an invalid call fails with MPI's own error string, on every rank alike.
TEST_F(CompositorMpi, MpiErrorsBecomeExceptionsWithMpiErrorString) {
  uint64_t v = 0;
  try {
    mpiWorld().broadcast(&v, sizeof v, mpiWorld().size());  // no such root
    ADD_FAILURE() << "expected comm::MpiError";
  } catch (const comm::MpiError& e) {
    EXPECT_NE(std::string(e.what()).find("MPI_Bcast"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("MPI_ERR_ROOT"), std::string::npos) << e.what();
  }
  mpiWorld().barrier();  // the communicator still works
}

// Run only by mpi_abort_check.sh: the last rank fails while the others wait for it in a frame;
// every process must end promptly with the message.
TEST_F(CompositorMpi, DISABLED_FailureOnOneRankEndsAllRanks) {
  comm::Communicator& comm = mpiWorld();
  WorldSpec s;
  s.ranks = comm.size();
  World w = makeWorld(s);
  RankRig rig(&comm, mpiContext(), s.width, s.height, {});
  rig.run(w);
  if (comm.rank() == comm.size() - 1)
    throw std::runtime_error("injected failure on rank " + std::to_string(comm.rank()));
  rig.run(w);
  ADD_FAILURE() << "rank " << comm.rank() << " finished a frame without the failed rank";
}

}  // namespace
}  // namespace sm::comp::test
