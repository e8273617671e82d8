// Typed reductions and the one-rank communicator: exact answers on 1 and several in-process ranks.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "comm/local_communicator.h"
#include "comm/reductions.h"
#include "comm/single_rank.h"

namespace sm::comm {
namespace {

// Values no two ranks share, negative and positive, with an infinity on the last rank.
double valueOf(int rank, int size) {
  if (rank == size - 1 && size > 2) return -std::numeric_limits<double>::infinity();
  return (rank % 2 ? -1.0 : 1.0) * (0.1 + rank * 1e-17 + rank);
}

void checkReductions(Communicator& c) {
  const int n = c.size();
  const double v = valueOf(c.rank(), n);
  double lo = valueOf(0, n), hi = lo, sum = 0;
  for (int r = 0; r < n; ++r) {
    lo = std::min(lo, valueOf(r, n));
    hi = std::max(hi, valueOf(r, n));
    sum += valueOf(r, n);  // rank order
  }
  EXPECT_EQ(minOf(c, v), lo);
  EXPECT_EQ(maxOf(c, v), hi);
  const double got = sumOf(c, v);
  if (std::isinf(sum))
    EXPECT_EQ(got, sum);
  else
    EXPECT_EQ(got, sum) << "summed in rank order, bit for bit";
  EXPECT_EQ(sumOf(c, uint64_t(c.rank() + 1)), uint64_t(n * (n + 1) / 2));
  EXPECT_EQ(maxOf(c, uint64_t(c.rank())), uint64_t(n - 1));
  EXPECT_TRUE(allSame(c, 42));
  EXPECT_EQ(allSame(c, uint64_t(c.rank())), n == 1);
  const std::vector<double> all = allValues(c, v);
  ASSERT_EQ(all.size(), size_t(n));
  for (int r = 0; r < n; ++r) EXPECT_EQ(all[r], valueOf(r, n));
  // Rank r sends r + d copies of 100 r + d to rank d.
  std::vector<std::vector<double>> toRank(n);
  for (int d = 0; d < n; ++d) toRank[d].assign(size_t(c.rank() + d), 100.0 * c.rank() + d);
  const auto fromRank = exchangeValues(c, toRank);
  ASSERT_EQ(fromRank.size(), size_t(n));
  for (int s = 0; s < n; ++s)
    EXPECT_EQ(fromRank[s], std::vector<double>(size_t(s + c.rank()), 100.0 * s + c.rank()));
  EXPECT_EQ(comm::broadcastString(c, c.rank() == 0 ? "from root" : "ignored"), "from root");
  const std::vector<std::string> names = {"pressure", "", "Mach number"};
  EXPECT_EQ(comm::broadcastNames(c, c.rank() == 0 ? names : std::vector<std::string>{"x"}), names);
  EXPECT_EQ(withPeers(c), n > 1 ? &c : nullptr);
}

TEST(Reductions, ExactOnOneRankAlone) {
  SingleRank one;
  checkReductions(one);
}

TEST(Reductions, ExactAndIdenticalOnEveryInProcessRank) {
  for (int n : {1, 2, 5}) runLocalRanks(n, [](Communicator& c) { checkReductions(c); });
}

TEST(Reductions, ExchangeNeedsOneListPerRank) {
  SingleRank one;
  EXPECT_THROW(exchangeValues(one, {{1.0}, {2.0}}), CommError);
}

TEST(SingleRank, CopiesToItselfAndRefusesWhatCannotMatch) {
  SingleRank one;
  const std::vector<uint64_t> sent = {7, 8, 9};
  std::vector<uint64_t> got(4, 0);
  const uint64_t sendBytes[] = {16}, sendOffsets[] = {8}, recvBytes[] = {16}, recvOffsets[] = {16};
  one.alltoallv(sent.data(), sendBytes, sendOffsets, got.data(), recvBytes, recvOffsets);
  EXPECT_EQ(got, (std::vector<uint64_t>{0, 0, 8, 9}));
  const uint64_t tooMany[] = {24};
  EXPECT_THROW(one.alltoallv(sent.data(), sendBytes, sendOffsets, got.data(), tooMany, recvOffsets),
               CommError);
  const uint64_t two[] = {8, 8};
  EXPECT_THROW(one.alltoallv(sent.data(), two, two, got.data(), two, two), CommError);
  EXPECT_THROW(one.gatherv(sent.data(), 8, got.data(), recvBytes, recvOffsets, 0), CommError);
  EXPECT_THROW(one.gatherv(sent.data(), 8, got.data(), sendBytes, recvOffsets, 1), CommError);
  try {
    one.abort("rank-wide failure");
    FAIL() << "abort returned";
  } catch (const CommError& e) {
    EXPECT_STREQ(e.what(), "rank-wide failure");
  }
}

}  // namespace
}  // namespace sm::comm
