// In-process ranks: N threads of one process share a LocalGroup and exchange through shared memory.
// Each thread owns its own vk::Context (lavapipe opens several), so a test runs the compositor's
// multi-rank path exactly as MPI ranks would, without mpirun.
#pragma once

#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "comm/communicator.h"

namespace sm::comm {

// The shared state of one group of in-process ranks: a reusable barrier and one posting slot per
// rank. A collective posts, meets the others at the barrier, reads their posts, and meets them
// again so that no rank reuses its buffers while another still reads them.
class LocalGroup {
 public:
  explicit LocalGroup(int size);
  int size() const { return size_; }

  struct Post {
    const void* data = nullptr;
    uint64_t bytes = 0;
    std::span<const uint64_t> sizes, offsets;
    uint64_t value = 0;
  };
  void post(int rank, const Post& p) { posts_[size_t(rank)] = p; }
  const Post& posted(int rank) const { return posts_[size_t(rank)]; }
  // Waits until every rank arrived; throws CommAborted once any rank aborted.
  void arrive();
  void abort(const std::string& message);

 private:
  int size_;
  std::mutex mutex_;
  std::condition_variable cv_;
  int waiting_ = 0;
  uint64_t generation_ = 0;
  bool aborted_ = false;
  std::string message_;
  std::vector<Post> posts_;
};

class LocalCommunicator : public Communicator {
 public:
  LocalCommunicator(std::shared_ptr<LocalGroup> group, int rank);
  int rank() const override { return rank_; }
  int size() const override { return group_->size(); }
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
  [[noreturn]] void abort(const std::string& message) override;

 private:
  void checkSpan(std::span<const uint64_t> s, const char* what) const;
  std::shared_ptr<LocalGroup> group_;
  int rank_;
};

// Runs fn on `ranks` threads, each with its own LocalCommunicator, and joins them. When a rank
// throws, the group is aborted (the others leave their collectives with CommAborted) and the first
// original error is rethrown here.
void runLocalRanks(int ranks, const std::function<void(Communicator&)>& fn);

}  // namespace sm::comm
