// The MPI communicator's host logic that needs no second process: transfer splitting and the
// thread-level check.
#include <gtest/gtest.h>

#include <climits>
#include <string>

#include "comm/mpi/mpi_communicator.h"
#include "comm/mpi/mpi_session.h"

namespace sm::comm {
namespace {

TEST(MpiChunks, TransfersBeyondIntSplitIntoPiecesThatFit) {
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

// An MPI that cannot have other threads running beside its calls is refused with a message (the
// MPI here gives what is asked, so the check is tested on its own).
TEST(MpiSession, ThreadLevelBelowFunneledIsRefused) {
  EXPECT_NO_THROW(checkThreadLevel(MPI_THREAD_FUNNELED));
  EXPECT_NO_THROW(checkThreadLevel(MPI_THREAD_MULTIPLE));
  try {
    checkThreadLevel(MPI_THREAD_SINGLE);
    FAIL() << "MPI_THREAD_SINGLE accepted";
  } catch (const CommError& e) {
    EXPECT_NE(std::string(e.what()).find("MPI_THREAD_FUNNELED"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sm::comm
