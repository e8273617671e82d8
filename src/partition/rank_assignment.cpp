// Longest-processing-time-first assignment of clusters to ranks: within 4/3 of the optimal
// maximum load, and deterministic because every tie has a fixed winner.
#include <algorithm>
#include <numeric>
#include <queue>

#include "common/error.h"
#include "partition/partition.h"

namespace sm::partition {

std::vector<int> assignClustersToRanks(const std::vector<uint64_t>& clusterSizes, int ranks) {
  if (ranks < 1) throw Error("the number of ranks must be at least 1, got ", ranks);
  std::vector<int> order(clusterSizes.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return clusterSizes[a] > clusterSizes[b]; });
  // (load, rank) pairs: the smallest pair is the least loaded rank, lowest rank on ties.
  using Load = std::pair<uint64_t, int>;
  std::priority_queue<Load, std::vector<Load>, std::greater<Load>> loads;
  for (int r = 0; r < ranks; ++r) loads.push({0, r});
  std::vector<int> clusterToRank(clusterSizes.size(), 0);
  for (int c : order) {
    if (clusterSizes[c] == 0) continue;
    Load least = loads.top();
    loads.pop();
    clusterToRank[c] = least.second;
    loads.push({least.first + clusterSizes[c], least.second});
  }
  return clusterToRank;
}

}  // namespace sm::partition
