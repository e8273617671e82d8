#include "app/comm_collectives.h"

#include <algorithm>
#include <numeric>
#include <vector>

#include "border/rank_exchange.h"

namespace sm::app {

std::vector<double> CommCollectives::allValues(double v) {
  const int n = comm_.size();
  std::vector<double> all(n);
  std::vector<uint64_t> bytes(n, sizeof(double)), offsets(n);
  for (int r = 0; r < n; ++r) offsets[r] = uint64_t(r) * sizeof(double);
  comm_.gatherv(&v, sizeof v, all.data(), bytes, offsets, 0);
  comm_.broadcast(all.data(), all.size() * sizeof(double), 0);
  return all;
}

double CommCollectives::min(double v) {
  auto all = allValues(v);
  return *std::min_element(all.begin(), all.end());
}

double CommCollectives::max(double v) {
  auto all = allValues(v);
  return *std::max_element(all.begin(), all.end());
}

double CommCollectives::sum(double v) {
  auto all = allValues(v);
  // Summed in rank order on every rank: the same result everywhere.
  return std::accumulate(all.begin(), all.end(), 0.0);
}

std::vector<std::vector<double>> CommCollectives::exchange(
    const std::vector<std::vector<double>>& toRank) {
  return border::exchangeThrough(comm_, toRank);
}

}  // namespace sm::app
