// Collectives for ranks that talk through the compositor's Communicator (MPI under mpirun).
#pragma once

#include "app/collectives.h"
#include "compositor/communicator.h"

namespace sm::app {

class CommCollectives final : public Collectives {
 public:
  explicit CommCollectives(comp::Communicator& comm) : comm_(comm) {}
  int rank() const override { return comm_.rank(); }
  int size() const override { return comm_.size(); }
  double min(double v) override;
  double max(double v) override;
  double sum(double v) override;
  uint64_t sum(uint64_t v) override { return comm_.allreduceSum(v); }
  void broadcast(void* data, uint64_t bytes) override { comm_.broadcast(data, bytes, 0); }
  void broadcastPatiently(void* data, uint64_t bytes) override {
    comm_.broadcastPatiently(data, bytes, 0);
  }
  std::vector<std::vector<double>> exchange(
      const std::vector<std::vector<double>>& toRank) override;
  // One rank needs no exchange: the compositor gets no communicator then.
  comp::Communicator* communicator() override { return comm_.size() > 1 ? &comm_ : nullptr; }

 private:
  // Every rank's value, on every rank (gather to rank 0, broadcast back).
  std::vector<double> allValues(double v);
  comp::Communicator& comm_;
};

}  // namespace sm::app
