// How ranks talk: the one interface the compositor, the border exchange, the application and the
// in-situ library use to reach their peers. The core (target shellmarch_comm) is MPI-free:
// SingleRank is one process alone, LocalCommunicator simulates ranks as threads of one process
// (tests); MpiCommunicator (target shellmarch_comm_mpi) wraps MPI. Typed reductions over any of
// them are free functions (reductions.h).
//
// Every size and offset is a 64-bit byte count: implementations that talk to an API with `int`
// counts (MPI) split transfers so that no count overflows. All calls except rank() and size() are
// collective or matched, and throw CommError on failure. abort() ends every rank with a message:
// an error on one rank must never leave the others waiting in a collective.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>

namespace sm::comm {

class CommError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Thrown on the ranks that did not fail when another rank aborted (in-process ranks only: MPI
// ends the processes instead).
class CommAborted : public CommError {
 public:
  using CommError::CommError;
};

class Communicator {
 public:
  virtual ~Communicator() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;

  virtual void barrier() = 0;
  virtual uint64_t allreduceMax(uint64_t value) = 0;
  virtual uint64_t allreduceSum(uint64_t value) = 0;
  // Rank r sends sendBytes[d] bytes at send + sendOffsets[d] to every rank d and receives
  // recvBytes[s] bytes from rank s at recv + recvOffsets[s]. All spans have size() entries.
  virtual void alltoallv(const void* send, std::span<const uint64_t> sendBytes,
                         std::span<const uint64_t> sendOffsets, void* recv,
                         std::span<const uint64_t> recvBytes,
                         std::span<const uint64_t> recvOffsets) = 0;
  // Every rank sends `bytes` at `send` to `root`, which receives rank s's part at
  // recv + recvOffsets[s] (recvBytes[s] must equal what s sends). recv* matter on root only.
  virtual void gatherv(const void* send, uint64_t bytes, void* recv,
                       std::span<const uint64_t> recvBytes, std::span<const uint64_t> recvOffsets,
                       int root) = 0;
  virtual void broadcast(void* data, uint64_t bytes, int root) = 0;
  // broadcast for ranks that may wait long for root (an interactive viewer's state while rank 0
  // waits for input or paces play): they sleep between polls instead of keeping a core busy, as
  // a blocking MPI broadcast does. Every rank of the group must call this one, not broadcast.
  virtual void broadcastPatiently(void* data, uint64_t bytes, int root) {
    broadcast(data, bytes, root);
  }
  // Ends all ranks with `message` (printed with this rank's number). Does not return.
  [[noreturn]] virtual void abort(const std::string& message) = 0;
};

// Runs fn; if it throws, aborts every rank with the error's message instead of unwinding into a
// state where the other ranks wait forever.
void runOrAbort(Communicator& comm, const std::function<void()>& fn);

}  // namespace sm::comm
