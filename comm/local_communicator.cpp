#include "comm/local_communicator.h"

#include <algorithm>
#include <cstring>
#include <exception>
#include <thread>

namespace sm::comm {

LocalGroup::LocalGroup(int size) : size_(size), posts_(size_t(std::max(size, 0))) {
  if (size < 1) throw CommError("local group: need at least one rank, not " + std::to_string(size));
}

void LocalGroup::arrive() {
  std::unique_lock lock(mutex_);
  if (aborted_) throw CommAborted(message_);
  const uint64_t gen = generation_;
  if (++waiting_ == size_) {
    waiting_ = 0;
    ++generation_;
    cv_.notify_all();
    return;
  }
  cv_.wait(lock, [&] { return generation_ != gen || aborted_; });
  if (generation_ == gen) throw CommAborted(message_);
}

void LocalGroup::abort(const std::string& message) {
  std::lock_guard lock(mutex_);
  if (!aborted_) message_ = message;
  aborted_ = true;
  cv_.notify_all();
}

LocalCommunicator::LocalCommunicator(std::shared_ptr<LocalGroup> group, int rank)
    : group_(std::move(group)), rank_(rank) {
  if (rank < 0 || rank >= group_->size())
    throw CommError("local communicator: rank " + std::to_string(rank) + " outside a group of " +
                    std::to_string(group_->size()));
}

void LocalCommunicator::checkSpan(std::span<const uint64_t> s, const char* what) const {
  if (s.size() != size_t(size()))
    throw CommError(std::string(what) + " has " + std::to_string(s.size()) + " entries for " +
                    std::to_string(size()) + " ranks");
}

void LocalCommunicator::barrier() {
  group_->arrive();
}

uint64_t LocalCommunicator::allreduceMax(uint64_t value) {
  group_->post(rank_, {.value = value});
  group_->arrive();
  uint64_t r = 0;
  for (int s = 0; s < size(); ++s) r = std::max(r, group_->posted(s).value);
  group_->arrive();
  return r;
}

uint64_t LocalCommunicator::allreduceSum(uint64_t value) {
  group_->post(rank_, {.value = value});
  group_->arrive();
  uint64_t r = 0;
  for (int s = 0; s < size(); ++s) r += group_->posted(s).value;
  group_->arrive();
  return r;
}

void LocalCommunicator::alltoallv(const void* send, std::span<const uint64_t> sendBytes,
                                  std::span<const uint64_t> sendOffsets, void* recv,
                                  std::span<const uint64_t> recvBytes,
                                  std::span<const uint64_t> recvOffsets) {
  checkSpan(sendBytes, "alltoallv send sizes");
  checkSpan(sendOffsets, "alltoallv send offsets");
  checkSpan(recvBytes, "alltoallv receive sizes");
  checkSpan(recvOffsets, "alltoallv receive offsets");
  group_->post(rank_, {.data = send, .sizes = sendBytes, .offsets = sendOffsets});
  group_->arrive();
  std::string error;
  for (int s = 0; s < size() && error.empty(); ++s) {
    const LocalGroup::Post& p = group_->posted(s);
    const uint64_t n = p.sizes[size_t(rank_)];
    if (n != recvBytes[size_t(s)]) {
      error = "alltoallv: rank " + std::to_string(s) + " sends " + std::to_string(n) +
              " bytes to rank " + std::to_string(rank_) + ", which expects " +
              std::to_string(recvBytes[size_t(s)]);
      break;
    }
    if (n)
      std::memcpy(static_cast<uint8_t*>(recv) + recvOffsets[size_t(s)],
                  static_cast<const uint8_t*>(p.data) + p.offsets[size_t(rank_)], n);
  }
  // Leave together even on a size mismatch, then fail: the others still read this rank's post.
  group_->arrive();
  if (!error.empty()) throw CommError(error);
}

void LocalCommunicator::gatherv(const void* send, uint64_t bytes, void* recv,
                                std::span<const uint64_t> recvBytes,
                                std::span<const uint64_t> recvOffsets, int root) {
  group_->post(rank_, {.data = send, .bytes = bytes});
  group_->arrive();
  std::string error;
  if (rank_ == root) {
    checkSpan(recvBytes, "gatherv receive sizes");
    checkSpan(recvOffsets, "gatherv receive offsets");
    for (int s = 0; s < size() && error.empty(); ++s) {
      const LocalGroup::Post& p = group_->posted(s);
      if (p.bytes != recvBytes[size_t(s)]) {
        error = "gatherv: rank " + std::to_string(s) + " sends " + std::to_string(p.bytes) +
                " bytes, root expects " + std::to_string(recvBytes[size_t(s)]);
      } else if (p.bytes) {
        std::memcpy(static_cast<uint8_t*>(recv) + recvOffsets[size_t(s)], p.data, p.bytes);
      }
    }
  }
  group_->arrive();
  if (!error.empty()) throw CommError(error);
}

void LocalCommunicator::broadcast(void* data, uint64_t bytes, int root) {
  group_->post(rank_, {.data = data, .bytes = bytes});
  group_->arrive();
  const LocalGroup::Post& p = group_->posted(root);
  const bool ok = p.bytes == bytes;
  if (ok && rank_ != root && bytes) std::memcpy(data, p.data, bytes);
  group_->arrive();
  if (!ok)
    throw CommError("broadcast: root sends " + std::to_string(p.bytes) + " bytes, rank " +
                    std::to_string(rank_) + " expects " + std::to_string(bytes));
}

void LocalCommunicator::abort(const std::string& message) {
  const std::string m = "rank " + std::to_string(rank_) + ": " + message;
  group_->abort(m);
  throw CommAborted(m);
}

void runLocalRanks(int ranks, const std::function<void(Communicator&)>& fn) {
  auto group = std::make_shared<LocalGroup>(ranks);
  std::vector<std::exception_ptr> errors(static_cast<size_t>(ranks));
  std::vector<std::thread> threads;
  threads.reserve(size_t(ranks));
  // A thread that cannot start (no memory for its stack, a thread limit) must end the ranks that
  // did start, which would otherwise wait for it in their first collective; and the started threads
  // must be joined before the error leaves, or their destructors terminate the process.
  auto startFailed = [&](int r, const std::exception& e) {
    const std::string m = "local ranks: cannot start rank " + std::to_string(r) + " of " +
                          std::to_string(ranks) + ": " + e.what();
    group->abort(m);
    for (auto& t : threads) t.join();
    throw CommError(m);
  };
  auto rankMain = [&](int r) {
    LocalCommunicator comm(group, r);
    try {
      fn(comm);
    } catch (const CommAborted&) {
      errors[size_t(r)] = std::current_exception();
    } catch (const std::exception& e) {
      errors[size_t(r)] = std::current_exception();
      group->abort("rank " + std::to_string(r) + ": " + e.what());
    }
  };
  for (int r = 0; r < ranks; ++r) {
    try {
      threads.emplace_back(rankMain, r);
    } catch (const std::exception& e) {  // std::system_error, or std::bad_alloc for its state
      startFailed(r, e);
    }
  }
  for (auto& t : threads) t.join();
  // Prefer the error that started it over the CommAborted the other ranks saw.
  std::exception_ptr first;
  for (auto& e : errors) {
    if (!e) continue;
    try {
      std::rethrow_exception(e);
    } catch (const CommAborted&) {
      if (!first) first = e;
    } catch (...) {
      std::rethrow_exception(e);
    }
  }
  if (first) std::rethrow_exception(first);
}

}  // namespace sm::comm
