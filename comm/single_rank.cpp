#include "comm/single_rank.h"

#include <cstring>

namespace sm::comm {
namespace {

void copyOwn(const void* send, uint64_t sendBytes, void* recv, uint64_t recvBytes,
             const char* call) {
  if (sendBytes != recvBytes)
    throw CommError(std::string(call) + ": rank 0 sends " + std::to_string(sendBytes) +
                    " bytes to itself but expects " + std::to_string(recvBytes));
  if (sendBytes) std::memcpy(recv, send, sendBytes);
}

}  // namespace

void SingleRank::alltoallv(const void* send, std::span<const uint64_t> sendBytes,
                           std::span<const uint64_t> sendOffsets, void* recv,
                           std::span<const uint64_t> recvBytes,
                           std::span<const uint64_t> recvOffsets) {
  if (sendBytes.size() != 1 || sendOffsets.size() != 1 || recvBytes.size() != 1 ||
      recvOffsets.size() != 1)
    throw CommError("alltoallv: one rank needs one entry per size and offset list");
  copyOwn(static_cast<const char*>(send) + sendOffsets[0], sendBytes[0],
          static_cast<char*>(recv) + recvOffsets[0], recvBytes[0], "alltoallv");
}

void SingleRank::gatherv(const void* send, uint64_t bytes, void* recv,
                         std::span<const uint64_t> recvBytes, std::span<const uint64_t> recvOffsets,
                         int root) {
  if (root != 0 || recvBytes.size() != 1 || recvOffsets.size() != 1)
    throw CommError("gatherv: one rank gathers to root 0 with one size and offset");
  copyOwn(send, bytes, static_cast<char*>(recv) + recvOffsets[0], recvBytes[0], "gatherv");
}

void SingleRank::abort(const std::string& message) {
  throw CommError(message);
}

}  // namespace sm::comm
