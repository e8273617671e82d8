#include "cli/run_parallel.h"

#include "comm/mpi/mpi_communicator.h"
#include "comm/mpi/mpi_session.h"
#include "comm/single_rank.h"
#include "common/error.h"
#include "common/log.h"

namespace sm::app {

void runParallel(const std::function<void(comm::Communicator&)>& body) {
  if (!comm::launchedByMpi()) {
    comm::SingleRank single;
    body(single);
    return;
  }
  comm::MpiSession session;
  comm::MpiCommunicator comm;
  if (comm.size() > 1) log::setPrefix(concat("[rank ", comm.rank(), "] "));
  // An error on any rank ends every rank with its message: never one rank waiting in a collective
  // for another that has given up.
  comm::runOrAbort(comm, [&] {
    try {
      body(comm);
    } catch (const comm::CommAborted&) {
      throw;
    } catch (const std::exception& e) {
      // Messages quote names from input files: one printable line on the terminal.
      throw std::runtime_error(printableLine(e.what()));
    }
  });
}

}  // namespace sm::app
