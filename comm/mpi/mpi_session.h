// MPI's lifetime for a program that may or may not run under mpirun.
#pragma once

namespace sm::comm {

// True when a process manager (OpenMPI, MPICH/PMI, PMIx) launched this process.
bool launchedByMpi();

// Throws CommError unless MPI's `provided` thread level is at least MPI_THREAD_FUNNELED: the
// program runs other threads (lavapipe's, the scalar prefetch) while the main thread calls MPI,
// which an MPI that gives MPI_THREAD_SINGLE does not allow.
void checkThreadLevel(int provided);

// MPI_Init_thread on construction (funneled, checked), MPI_Finalize on destruction.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

}  // namespace sm::comm
