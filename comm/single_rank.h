// One process alone as a group of one: every collective is a local copy or nothing, so code
// written against Communicator runs without MPI and without special cases for one rank.
#pragma once

#include "comm/communicator.h"

namespace sm::comm {

class SingleRank final : public Communicator {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  void barrier() override {}
  uint64_t allreduceMax(uint64_t value) override { return value; }
  uint64_t allreduceSum(uint64_t value) override { return value; }
  void alltoallv(const void* send, std::span<const uint64_t> sendBytes,
                 std::span<const uint64_t> sendOffsets, void* recv,
                 std::span<const uint64_t> recvBytes,
                 std::span<const uint64_t> recvOffsets) override;
  void gatherv(const void* send, uint64_t bytes, void* recv, std::span<const uint64_t> recvBytes,
               std::span<const uint64_t> recvOffsets, int root) override;
  void broadcast(void*, uint64_t, int) override {}
  // No other rank to end: the message becomes a CommError for the caller.
  [[noreturn]] void abort(const std::string& message) override;
};

}  // namespace sm::comm
