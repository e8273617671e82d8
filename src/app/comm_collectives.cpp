#include "app/comm_collectives.h"

#include <algorithm>
#include <numeric>
#include <vector>

#include "common/check.h"

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
  const int n = comm_.size();
  SM_CHECK_EQ(toRank.size(), size_t(n));
  // The lengths first (8 bytes to every rank), then the values in one call.
  std::vector<uint64_t> sendCount(n), recvCount(n), eight(n, sizeof(uint64_t)), slot(n);
  for (int r = 0; r < n; ++r) {
    sendCount[r] = toRank[r].size();
    slot[r] = uint64_t(r) * sizeof(uint64_t);
  }
  comm_.alltoallv(sendCount.data(), eight, slot, recvCount.data(), eight, slot);
  std::vector<double> send, recv;
  std::vector<uint64_t> sendBytes(n), sendOffsets(n), recvBytes(n), recvOffsets(n);
  uint64_t recvTotal = 0;
  for (int r = 0; r < n; ++r) {
    sendOffsets[r] = send.size() * sizeof(double);
    sendBytes[r] = toRank[r].size() * sizeof(double);
    send.insert(send.end(), toRank[r].begin(), toRank[r].end());
    recvOffsets[r] = recvTotal * sizeof(double);
    recvBytes[r] = recvCount[r] * sizeof(double);
    recvTotal += recvCount[r];
  }
  recv.resize(recvTotal);
  comm_.alltoallv(send.data(), sendBytes, sendOffsets, recv.data(), recvBytes, recvOffsets);
  std::vector<std::vector<double>> fromRank(n);
  for (int r = 0; r < n; ++r) {
    const auto first = recv.begin() + ptrdiff_t(recvOffsets[r] / sizeof(double));
    fromRank[r].assign(first, first + ptrdiff_t(recvCount[r]));
  }
  return fromRank;
}

}  // namespace sm::app
