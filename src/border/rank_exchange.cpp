#include "border/rank_exchange.h"

#include <cstdint>

#include "common/check.h"
#include "compositor/communicator.h"

namespace sm::border {

std::vector<std::vector<double>> exchangeThrough(comp::Communicator& comm,
                                                 const std::vector<std::vector<double>>& toRank) {
  const int n = comm.size();
  SM_CHECK_EQ(toRank.size(), size_t(n));
  // The lengths first (8 bytes to every rank), then the values in one call.
  std::vector<uint64_t> sendCount(n), recvCount(n), eight(n, sizeof(uint64_t)), slot(n);
  for (int r = 0; r < n; ++r) {
    sendCount[r] = toRank[r].size();
    slot[r] = uint64_t(r) * sizeof(uint64_t);
  }
  comm.alltoallv(sendCount.data(), eight, slot, recvCount.data(), eight, slot);
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
  comm.alltoallv(send.data(), sendBytes, sendOffsets, recv.data(), recvBytes, recvOffsets);
  std::vector<std::vector<double>> fromRank(n);
  for (int r = 0; r < n; ++r) {
    const auto first = recv.begin() + ptrdiff_t(recvOffsets[r] / sizeof(double));
    fromRank[r].assign(first, first + ptrdiff_t(recvCount[r]));
  }
  return fromRank;
}

}  // namespace sm::border
