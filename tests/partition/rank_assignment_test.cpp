#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "common/error.h"
#include "partition/partition.h"

namespace sm::partition {
namespace {

std::vector<uint64_t> loads(const std::vector<uint64_t>& sizes, const std::vector<int>& rankOf,
                            int ranks) {
  std::vector<uint64_t> load(ranks, 0);
  for (size_t c = 0; c < sizes.size(); ++c) load[rankOf[c]] += sizes[c];
  return load;
}

TEST(AssignClustersToRanks, LargestFirstOntoLeastLoaded) {
  // 10 -> 0, 9 -> 1, 8 -> 1 (9 < 10), 7 -> 0 (10 < 17), 6 -> 0 (17 = 17: lowest rank), 5 -> 1.
  const std::vector<uint64_t> sizes = {10, 9, 8, 7, 6, 5};
  EXPECT_EQ(assignClustersToRanks(sizes, 2), (std::vector<int>{0, 1, 1, 0, 0, 1}));
  // Cluster order does not matter, only sizes; equal sizes go in cluster order.
  EXPECT_EQ(assignClustersToRanks({5, 5, 5, 5}, 3), (std::vector<int>{0, 1, 2, 0}));
}

TEST(AssignClustersToRanks, EmptyClustersGoToRankZeroAndExtraRanksStayEmpty) {
  EXPECT_EQ(assignClustersToRanks({0, 4, 0, 3}, 2), (std::vector<int>{0, 0, 0, 1}));
  EXPECT_EQ(assignClustersToRanks({7, 2}, 5), (std::vector<int>{0, 1}));
  EXPECT_TRUE(assignClustersToRanks({}, 3).empty());
}

TEST(AssignClustersToRanks, StaysWithinTheLptBound) {
  // Deterministic pseudo-random sizes; LPT's makespan is at most the mean load plus one cluster.
  std::vector<uint64_t> sizes;
  uint64_t x = 12345;
  for (int i = 0; i < 97; ++i) {
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    sizes.push_back(1 + (x >> 33) % 1000);
  }
  const uint64_t total = std::accumulate(sizes.begin(), sizes.end(), uint64_t(0));
  const uint64_t largest = *std::max_element(sizes.begin(), sizes.end());
  for (int ranks : {1, 2, 3, 7, 16}) {
    auto rankOf = assignClustersToRanks(sizes, ranks);
    ASSERT_EQ(rankOf.size(), sizes.size());
    for (int r : rankOf) ASSERT_TRUE(r >= 0 && r < ranks);
    auto load = loads(sizes, rankOf, ranks);
    EXPECT_LE(*std::max_element(load.begin(), load.end()), total / ranks + largest) << ranks;
    EXPECT_EQ(std::accumulate(load.begin(), load.end(), uint64_t(0)), total);
  }
}

TEST(AssignClustersToRanks, RejectsNoRanks) {
  EXPECT_THROW(assignClustersToRanks({1, 2}, 0), Error);
}

}  // namespace
}  // namespace sm::partition
