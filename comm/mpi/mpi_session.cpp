#include "comm/mpi/mpi_session.h"

#include <mpi.h>

#include <cstdlib>
#include <string>

#include "comm/mpi/mpi_communicator.h"

namespace sm::comm {

bool launchedByMpi() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
    if (std::getenv(var)) return true;
  return false;
}

void checkThreadLevel(int provided) {
  if (provided >= MPI_THREAD_FUNNELED) return;
  throw CommError("MPI_Init_thread: this MPI provides thread level " + std::to_string(provided) +
                  " (MPI_THREAD_SINGLE), shellmarch needs MPI_THREAD_FUNNELED (" +
                  std::to_string(MPI_THREAD_FUNNELED) +
                  "): other threads run while the main thread calls MPI");
}

MpiSession::MpiSession() {
  int provided = 0;
  mpiCheck(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  try {
    checkThreadLevel(provided);
  } catch (...) {
    MPI_Finalize();  // the destructor of an object whose constructor threw does not run
    throw;
  }
  // Errors come back as codes from here on, so that they become messages instead of silent aborts.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
}

MpiSession::~MpiSession() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

}  // namespace sm::comm
