// The ranks one in-situ Renderer runs on: an MPI communicator, or this process alone. Reductions go
// through comm/reductions.h on comm(); what the group adds is agreeing on failures: a failure on
// one rank becomes the same exception on every rank (agree), so that no rank waits in a collective
// for one that has given up.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "comm/communicator.h"

namespace sm::insitu {

class Group final {
 public:
  Group();                        // this process alone: no MPI calls
  explicit Group(MPI_Comm comm);  // collective: duplicates comm

  int rank() const { return comm_->rank(); }
  int size() const { return comm_->size(); }
  comm::Communicator& comm() { return *comm_; }

  // Runs `local` (which must not communicate), then agrees: when it threw on any rank, every rank
  // throws shellmarch::insitu::Error with the message of the lowest failed rank, prefixed by that
  // rank's number when there are several ranks.
  void agree(const std::function<void()>& local);
  // For work inside collectives (where agreeing afterwards is impossible): an exception ends every
  // rank with its message (MPI_Abort). On one rank the exception passes through unchanged.
  void runOrAbort(const std::function<void()>& fn);

 private:
  std::unique_ptr<comm::Communicator> comm_;
};

}  // namespace sm::insitu
