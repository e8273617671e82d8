// The ranks one in-situ Renderer runs on: an MPI communicator, or this process alone. Besides the
// reductions the frame needs, it turns a failure on one rank into the same exception on every rank
// (agree), so that no rank waits in a collective for one that has given up.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "border/rank_exchange.h"
#include "compositor/mpi/mpi_communicator.h"

namespace sm::insitu {

class Group final : public border::RankExchange {
 public:
  Group() = default;              // this process alone: no MPI calls
  explicit Group(MPI_Comm comm);  // collective: duplicates comm
  int rank() const override { return comm_ ? comm_->rank() : 0; }
  int size() const override { return comm_ ? comm_->size() : 1; }
  // What the compositor exchanges through; nullptr for one rank (no exchange at all).
  comp::Communicator* compositorComm() { return size() > 1 ? comm_.get() : nullptr; }

  // Collective reductions, exact and identical on every rank.
  double min(double v);
  double max(double v);
  double sum(double v);  // summed in rank order
  uint64_t sum(uint64_t v);
  bool same(uint64_t v);  // every rank passed the same value
  // Collective (cell fields' sums at shared vertices).
  std::vector<std::vector<double>> exchange(
      const std::vector<std::vector<double>>& toRank) override;

  // Runs `local` (which must not communicate), then agrees: when it threw on any rank, every rank
  // throws shellmarch::insitu::Error with the message of the lowest failed rank, prefixed by that
  // rank's number when there are several ranks.
  void agree(const std::function<void()>& local);
  // For work inside collectives (where agreeing afterwards is impossible): an exception ends every
  // rank with its message (MPI_Abort). On one rank the exception passes through unchanged.
  void runOrAbort(const std::function<void()>& fn);

 private:
  std::unique_ptr<comp::MpiCommunicator> comm_;
};

}  // namespace sm::insitu
