// Communicator over MPI (target shellmarch_comm_mpi). Works on a duplicate of the given
// communicator with MPI_ERRORS_RETURN, so every MPI failure becomes an MpiError carrying the call
// and MPI's error string instead of killing the job silently.
//
// MPI counts and displacements are `int`; transfers are split so that none exceeds
// maxMessageBytes (default 1 GiB): alltoallv uses MPI_Alltoallv while every size and offset fits,
// and otherwise MPI_Alltoallw over MPI_BOTTOM with one derived datatype per peer (absolute 64-bit
// addresses, whole chunks plus a tail); gatherv posts one receive per rank and chunk on the root.
#pragma once

#include <mpi.h>

#include "comm/communicator.h"

namespace sm::comm {

class MpiError : public CommError {
 public:
  MpiError(const std::string& call, int code);
  int code() const { return code_; }

 private:
  int code_;
};

// Throws MpiError when rc is not MPI_SUCCESS.
void mpiCheck(int rc, const char* call);

class MpiCommunicator : public Communicator {
 public:
  // Duplicates `comm` (MPI must be initialised and stay so while this object lives).
  explicit MpiCommunicator(MPI_Comm comm = MPI_COMM_WORLD);
  ~MpiCommunicator() override;
  MpiCommunicator(const MpiCommunicator&) = delete;
  MpiCommunicator& operator=(const MpiCommunicator&) = delete;

  // Largest byte count of one MPI message or datatype block; tests force it small.
  void setMaxMessageBytes(uint64_t bytes);
  uint64_t maxMessageBytes() const { return maxBytes_; }
  // Collectives so far that had to split a transfer (derived datatypes or several messages).
  uint64_t splitTransfers() const { return splitTransfers_; }
  MPI_Comm handle() const { return comm_; }

  int rank() const override { return rank_; }
  int size() const override { return size_; }
  void barrier() override;
  uint64_t allreduceMax(uint64_t value) override;
  uint64_t allreduceSum(uint64_t value) override;
  void alltoallv(const void* send, std::span<const uint64_t> sendBytes,
                 std::span<const uint64_t> sendOffsets, void* recv,
                 std::span<const uint64_t> recvBytes,
                 std::span<const uint64_t> recvOffsets) override;
  void gatherv(const void* send, uint64_t bytes, void* recv, std::span<const uint64_t> recvBytes,
               std::span<const uint64_t> recvOffsets, int root) override;
  void broadcast(void* data, uint64_t bytes, int root) override;
  void broadcastPatiently(void* data, uint64_t bytes, int root) override;
  // Prints the message on stderr and calls MPI_Abort on MPI_COMM_WORLD: every rank ends.
  [[noreturn]] void abort(const std::string& message) override;

 private:
  bool fitsInt(std::span<const uint64_t> a, std::span<const uint64_t> b) const;
  void alltoallvInt(const void* send, std::span<const uint64_t> sendBytes,
                    std::span<const uint64_t> sendOffsets, void* recv,
                    std::span<const uint64_t> recvBytes, std::span<const uint64_t> recvOffsets);
  void alltoallvTyped(const void* send, std::span<const uint64_t> sendBytes,
                      std::span<const uint64_t> sendOffsets, void* recv,
                      std::span<const uint64_t> recvBytes, std::span<const uint64_t> recvOffsets);
  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0, size_ = 1;
  uint64_t maxBytes_ = uint64_t(1) << 30;
  uint64_t splitTransfers_ = 0;
};

// Splits a transfer of `bytes` into pieces of at most maxBytes (the last one shorter); exposed for
// tests of sizes that do not fit in memory.
struct ChunkPlan {
  uint64_t chunks;  // whole pieces of maxBytes
  uint64_t tail;    // bytes after them (< maxBytes)
};
ChunkPlan planChunks(uint64_t bytes, uint64_t maxBytes);

}  // namespace sm::comm
