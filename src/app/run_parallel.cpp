#include "app/run_parallel.h"

#include "app/comm_collectives.h"
#include "common/error.h"
#include "common/log.h"
#include "compositor/mpi/mpi_communicator.h"
#include "compositor/mpi/mpi_session.h"

namespace sm::app {

void runParallel(const std::function<void(Collectives&)>& body) {
  if (!comp::launchedByMpi()) {
    SingleProcess single;
    body(single);
    return;
  }
  comp::MpiSession session;
  comp::MpiCommunicator comm;
  if (comm.size() > 1) log::setPrefix(concat("[rank ", comm.rank(), "] "));
  CommCollectives coll(comm);
  // An error on any rank ends every rank with its message: never one rank waiting in a collective
  // for another that has given up.
  comp::runOrAbort(comm, [&] {
    try {
      body(coll);
    } catch (const comp::CommAborted&) {
      throw;
    } catch (const std::exception& e) {
      // Messages quote names from input files: one printable line on the terminal.
      throw std::runtime_error(printableLine(e.what()));
    }
  });
}

}  // namespace sm::app
