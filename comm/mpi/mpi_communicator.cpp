#include "comm/mpi/mpi_communicator.h"

#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

namespace sm::comm {
namespace {

std::string errorString(int code) {
  char text[MPI_MAX_ERROR_STRING] = {};
  int len = 0;
  if (MPI_Error_string(code, text, &len) != MPI_SUCCESS) return "MPI error " + std::to_string(code);
  return std::string(text, size_t(len));
}

// Frees derived datatypes on every path out of a collective.
struct TypeList {
  std::vector<MPI_Datatype> types;
  ~TypeList() {
    for (MPI_Datatype& t : types)
      if (t != MPI_BYTE && t != MPI_DATATYPE_NULL) MPI_Type_free(&t);
  }
};

}  // namespace

MpiError::MpiError(const std::string& call, int code)
    : CommError(call + " failed: " + errorString(code)), code_(code) {}

void mpiCheck(int rc, const char* call) {
  if (rc != MPI_SUCCESS) throw MpiError(call, rc);
}

ChunkPlan planChunks(uint64_t bytes, uint64_t maxBytes) {
  if (maxBytes == 0) throw CommError("chunk size must be at least one byte");
  return {bytes / maxBytes, bytes % maxBytes};
}

MpiCommunicator::MpiCommunicator(MPI_Comm comm) {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) throw CommError("MpiCommunicator: MPI is not initialised");
  // Errors on the duplicate return to us; the parent communicator keeps its own handler.
  mpiCheck(MPI_Comm_dup(comm, &comm_), "MPI_Comm_dup");
  mpiCheck(MPI_Comm_set_errhandler(comm_, MPI_ERRORS_RETURN), "MPI_Comm_set_errhandler");
  mpiCheck(MPI_Comm_rank(comm_, &rank_), "MPI_Comm_rank");
  mpiCheck(MPI_Comm_size(comm_, &size_), "MPI_Comm_size");
}

MpiCommunicator::~MpiCommunicator() {
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (!finalised && comm_ != MPI_COMM_NULL) MPI_Comm_free(&comm_);
}

void MpiCommunicator::setMaxMessageBytes(uint64_t bytes) {
  if (bytes == 0 || bytes > uint64_t(INT_MAX))
    throw CommError("MPI message size limit must be in [1, INT_MAX], not " + std::to_string(bytes));
  maxBytes_ = bytes;
}

void MpiCommunicator::barrier() {
  mpiCheck(MPI_Barrier(comm_), "MPI_Barrier");
}

uint64_t MpiCommunicator::allreduceMax(uint64_t value) {
  uint64_t r = 0;
  mpiCheck(MPI_Allreduce(&value, &r, 1, MPI_UINT64_T, MPI_MAX, comm_), "MPI_Allreduce(max)");
  return r;
}

uint64_t MpiCommunicator::allreduceSum(uint64_t value) {
  uint64_t r = 0;
  mpiCheck(MPI_Allreduce(&value, &r, 1, MPI_UINT64_T, MPI_SUM, comm_), "MPI_Allreduce(sum)");
  return r;
}

bool MpiCommunicator::fitsInt(std::span<const uint64_t> a, std::span<const uint64_t> b) const {
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i] > maxBytes_ || b[i] > maxBytes_) return false;
  return true;
}

void MpiCommunicator::alltoallv(const void* send, std::span<const uint64_t> sendBytes,
                                std::span<const uint64_t> sendOffsets, void* recv,
                                std::span<const uint64_t> recvBytes,
                                std::span<const uint64_t> recvOffsets) {
  const size_t n = size_t(size_);
  if (sendBytes.size() != n || sendOffsets.size() != n || recvBytes.size() != n ||
      recvOffsets.size() != n)
    throw CommError("alltoallv: size and offset arrays need one entry per rank (" +
                    std::to_string(n) + ")");
  // Every rank must take the same path: the choice depends on all ranks' sizes.
  const uint64_t fits = fitsInt(sendBytes, sendOffsets) && fitsInt(recvBytes, recvOffsets);
  const bool allFit = allreduceMax(fits ? 0 : 1) == 0;
  if (allFit)
    alltoallvInt(send, sendBytes, sendOffsets, recv, recvBytes, recvOffsets);
  else
    alltoallvTyped(send, sendBytes, sendOffsets, recv, recvBytes, recvOffsets);
}

void MpiCommunicator::alltoallvInt(const void* send, std::span<const uint64_t> sendBytes,
                                   std::span<const uint64_t> sendOffsets, void* recv,
                                   std::span<const uint64_t> recvBytes,
                                   std::span<const uint64_t> recvOffsets) {
  std::vector<int> sc(sendBytes.begin(), sendBytes.end()),
      sd(sendOffsets.begin(), sendOffsets.end());
  std::vector<int> rc(recvBytes.begin(), recvBytes.end()),
      rd(recvOffsets.begin(), recvOffsets.end());
  mpiCheck(MPI_Alltoallv(send, sc.data(), sd.data(), MPI_BYTE, recv, rc.data(), rd.data(), MPI_BYTE,
                         comm_),
           "MPI_Alltoallv");
}

namespace {

// One datatype describing `bytes` bytes at absolute address `at` (used with MPI_BOTTOM): whole
// chunks of maxBytes, then the tail, so that no block count exceeds INT_MAX.
MPI_Datatype spanType(const void* at, uint64_t bytes, uint64_t maxBytes, MPI_Datatype chunk) {
  ChunkPlan plan = planChunks(bytes, maxBytes);
  if (plan.chunks > uint64_t(INT_MAX))
    throw CommError("alltoallv: " + std::to_string(bytes) + " bytes need more than INT_MAX chunks");
  MPI_Aint base = 0;
  mpiCheck(MPI_Get_address(at, &base), "MPI_Get_address");
  int lengths[2];
  MPI_Aint displs[2];
  MPI_Datatype types[2];
  int blocks = 0;
  if (plan.chunks) {
    lengths[blocks] = int(plan.chunks);
    displs[blocks] = base;
    types[blocks++] = chunk;
  }
  if (plan.tail) {
    lengths[blocks] = int(plan.tail);
    displs[blocks] = MPI_Aint_add(base, MPI_Aint(plan.chunks * maxBytes));
    types[blocks++] = MPI_BYTE;
  }
  MPI_Datatype t;
  mpiCheck(MPI_Type_create_struct(blocks, lengths, displs, types, &t), "MPI_Type_create_struct");
  int rc = MPI_Type_commit(&t);
  if (rc != MPI_SUCCESS) {
    MPI_Type_free(&t);
    throw MpiError("MPI_Type_commit", rc);
  }
  return t;
}

}  // namespace

void MpiCommunicator::alltoallvTyped(const void* send, std::span<const uint64_t> sendBytes,
                                     std::span<const uint64_t> sendOffsets, void* recv,
                                     std::span<const uint64_t> recvBytes,
                                     std::span<const uint64_t> recvOffsets) {
  const size_t n = size_t(size_);
  TypeList types;
  MPI_Datatype chunk;
  mpiCheck(MPI_Type_contiguous(int(maxBytes_), MPI_BYTE, &chunk), "MPI_Type_contiguous");
  types.types.push_back(chunk);
  mpiCheck(MPI_Type_commit(&types.types.back()), "MPI_Type_commit");
  chunk = types.types.back();
  std::vector<int> sc(n), rc(n), zero(n, 0);
  std::vector<MPI_Datatype> st(n, MPI_BYTE), rt(n, MPI_BYTE);
  auto describe = [&](const void* base, uint64_t offset, uint64_t bytes, int& count,
                      MPI_Datatype& type) {
    if (bytes == 0) return;
    type = spanType(static_cast<const uint8_t*>(base) + offset, bytes, maxBytes_, chunk);
    types.types.push_back(type);
    count = 1;
  };
  for (size_t i = 0; i < n; ++i) {
    describe(send, sendOffsets[i], sendBytes[i], sc[i], st[i]);
    describe(recv, recvOffsets[i], recvBytes[i], rc[i], rt[i]);
  }
  ++splitTransfers_;
  mpiCheck(MPI_Alltoallw(MPI_BOTTOM, sc.data(), zero.data(), st.data(), MPI_BOTTOM, rc.data(),
                         zero.data(), rt.data(), comm_),
           "MPI_Alltoallw");
}

void MpiCommunicator::gatherv(const void* send, uint64_t bytes, void* recv,
                              std::span<const uint64_t> recvBytes,
                              std::span<const uint64_t> recvOffsets, int root) {
  const int tag = 7;
  if (bytes > maxBytes_) ++splitTransfers_;
  if (rank_ != root) {
    for (uint64_t done = 0; done < bytes; done += maxBytes_) {
      int n = int(std::min(maxBytes_, bytes - done));
      mpiCheck(MPI_Send(static_cast<const uint8_t*>(send) + done, n, MPI_BYTE, root, tag, comm_),
               "MPI_Send");
    }
    return;
  }
  if (recvBytes.size() != size_t(size_) || recvOffsets.size() != size_t(size_))
    throw CommError("gatherv: root needs one size and offset per rank");
  if (recvBytes[size_t(rank_)] != bytes)
    throw CommError("gatherv: root sends itself " + std::to_string(bytes) + " bytes, expects " +
                    std::to_string(recvBytes[size_t(rank_)]));
  std::vector<MPI_Request> requests;
  for (int s = 0; s < size_; ++s) {
    if (s == root) continue;
    uint8_t* at = static_cast<uint8_t*>(recv) + recvOffsets[size_t(s)];
    for (uint64_t done = 0; done < recvBytes[size_t(s)]; done += maxBytes_) {
      int n = int(std::min(maxBytes_, recvBytes[size_t(s)] - done));
      requests.emplace_back();
      mpiCheck(MPI_Irecv(at + done, n, MPI_BYTE, s, tag, comm_, &requests.back()), "MPI_Irecv");
    }
  }
  if (bytes) std::memcpy(static_cast<uint8_t*>(recv) + recvOffsets[size_t(rank_)], send, bytes);
  std::vector<MPI_Status> status(requests.size());
  int rc = MPI_Waitall(int(requests.size()), requests.data(), status.data());
  if (rc == MPI_ERR_IN_STATUS) {
    for (const MPI_Status& s : status)
      if (s.MPI_ERROR != MPI_SUCCESS) throw MpiError("MPI_Waitall (gather receive)", s.MPI_ERROR);
  }
  mpiCheck(rc, "MPI_Waitall");
}

void MpiCommunicator::broadcast(void* data, uint64_t bytes, int root) {
  for (uint64_t done = 0; done < bytes; done += maxBytes_) {
    int n = int(std::min(maxBytes_, bytes - done));
    mpiCheck(MPI_Bcast(static_cast<uint8_t*>(data) + done, n, MPI_BYTE, root, comm_), "MPI_Bcast");
  }
}

void MpiCommunicator::broadcastPatiently(void* data, uint64_t bytes, int root) {
  for (uint64_t done = 0; done < bytes; done += maxBytes_) {
    int n = int(std::min(maxBytes_, bytes - done));
    MPI_Request request;
    mpiCheck(MPI_Ibcast(static_cast<uint8_t*>(data) + done, n, MPI_BYTE, root, comm_, &request),
             "MPI_Ibcast");
    // A few quick polls first (a frame's state usually arrives at once), then sleeps doubling to
    // a millisecond: at most a millisecond late, and an idle rank costs no core.
    std::chrono::microseconds pause(10);
    for (int polls = 0;; ++polls) {
      int finished = 0;
      mpiCheck(MPI_Test(&request, &finished, MPI_STATUS_IGNORE), "MPI_Test");
      if (finished) break;
      if (polls < 100) continue;
      std::this_thread::sleep_for(pause);
      pause = std::min(2 * pause, std::chrono::microseconds(1000));
    }
  }
}

void MpiCommunicator::abort(const std::string& message) {
  // A bad input fails every rank the same way: rank 0 reports and aborts the group at once; the
  // others wait two seconds first, so that one line is printed instead of one per rank (and Open
  // MPI's own complaints about simultaneous aborts). A rank failing alone still reports.
  if (rank_ != 0) std::this_thread::sleep_for(std::chrono::seconds(2));
  std::fprintf(stderr, "shellmarch: rank %d of %d failed: %s\n", rank_, size_, message.c_str());
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, 1);
  std::abort();  // MPI_Abort does not return; this keeps [[noreturn]] honest if it did
}

}  // namespace sm::comm
