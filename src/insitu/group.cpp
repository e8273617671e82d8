#include "group.h"

#include <string>
#include <vector>

#include "comm/mpi/mpi_communicator.h"
#include "comm/single_rank.h"
#include "common/error.h"
#include "shellmarch/insitu.h"

namespace sm::insitu {
Group::Group() : comm_(std::make_unique<comm::SingleRank>()) {}

Group::Group(MPI_Comm comm) : comm_(std::make_unique<comm::MpiCommunicator>(comm)) {}

void Group::agree(const std::function<void()>& local) {
  std::string message;
  bool failed = false;
  try {
    local();
  } catch (const std::exception& e) {
    message = e.what();
    failed = true;
  }
  if (size() == 1) {
    if (failed) throw shellmarch::insitu::Error(message);
    return;
  }
  // The lowest failed rank speaks for all: size - rank is largest for it.
  const int n = size();
  const uint64_t key = comm_->allreduceMax(failed ? uint64_t(n - rank()) : 0);
  if (key == 0) return;
  const int first = n - int(key);
  uint64_t length = rank() == first ? message.size() : 0;
  comm_->broadcast(&length, sizeof length, first);
  std::string text(length, '\0');
  if (rank() == first) text = message;
  comm_->broadcast(text.data(), length, first);
  if (n == 1) throw shellmarch::insitu::Error(text);
  std::string what = concat("rank ", first, ": ", text);
  if (failed && rank() != first)
    what += concat(" (this rank, ", rank(), ", also failed: ", message, ")");
  throw shellmarch::insitu::Error(what);
}

void Group::runOrAbort(const std::function<void()>& fn) {
  if (size() > 1)
    comm::runOrAbort(*comm_, fn);
  else
    fn();
}

}  // namespace sm::insitu
