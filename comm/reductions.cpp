#include "comm/reductions.h"

#include <algorithm>
#include <bit>
#include <numeric>

namespace sm::comm {
namespace {

// Order-preserving map of doubles to unsigned integers (NaN aside): the integer maximum of the
// mapped values is the mapped maximum.
uint64_t orderedBits(double v) {
  const uint64_t b = std::bit_cast<uint64_t>(v);
  return (b >> 63) ? ~b : b | (uint64_t(1) << 63);
}

double fromOrderedBits(uint64_t b) {
  return std::bit_cast<double>((b >> 63) ? b & ~(uint64_t(1) << 63) : ~b);
}

}  // namespace

double maxOf(Communicator& comm, double v) {
  return fromOrderedBits(comm.allreduceMax(orderedBits(v)));
}

double minOf(Communicator& comm, double v) {
  return -maxOf(comm, -v);
}

uint64_t maxOf(Communicator& comm, uint64_t v) {
  return comm.allreduceMax(v);
}

uint64_t sumOf(Communicator& comm, uint64_t v) {
  return comm.allreduceSum(v);
}

double sumOf(Communicator& comm, double v) {
  const std::vector<double> all = allValues(comm, v);
  return std::accumulate(all.begin(), all.end(), 0.0);
}

bool allSame(Communicator& comm, uint64_t v) {
  return comm.allreduceMax(v) == ~comm.allreduceMax(~v);
}

std::vector<double> allValues(Communicator& comm, double v) {
  const int n = comm.size();
  std::vector<double> all(size_t(n), v);
  if (n == 1) return all;
  std::vector<uint64_t> bytes(static_cast<size_t>(n), sizeof(double));
  std::vector<uint64_t> offsets(static_cast<size_t>(n));
  for (int r = 0; r < n; ++r) offsets[size_t(r)] = uint64_t(r) * sizeof(double);
  comm.gatherv(&v, sizeof v, all.data(), bytes, offsets, 0);
  comm.broadcast(all.data(), all.size() * sizeof(double), 0);
  return all;
}

std::vector<std::vector<double>> exchangeValues(Communicator& comm,
                                                const std::vector<std::vector<double>>& toRank) {
  const int n = comm.size();
  if (toRank.size() != size_t(n))
    throw CommError("exchange: " + std::to_string(toRank.size()) + " lists for " +
                    std::to_string(n) + " ranks");
  if (n == 1) return toRank;
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

std::string broadcastString(Communicator& comm, std::string text) {
  uint64_t bytes = text.size();
  comm.broadcast(&bytes, sizeof bytes, 0);
  text.resize(bytes);
  comm.broadcast(text.data(), bytes, 0);
  return text;
}

std::vector<std::string> broadcastNames(Communicator& comm, std::vector<std::string> names) {
  std::string joined;
  for (const std::string& n : names) joined += n + '\n';
  joined = broadcastString(comm, std::move(joined));
  names.clear();
  for (size_t start = 0, end; (end = joined.find('\n', start)) != std::string::npos;
       start = end + 1)
    names.push_back(joined.substr(start, end - start));
  return names;
}

}  // namespace sm::comm
