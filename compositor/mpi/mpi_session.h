// MPI's lifetime for a program that may or may not run under mpirun.
#pragma once

namespace sm::comp {

// True when a process manager (OpenMPI, MPICH/PMI, PMIx) launched this process.
bool launchedByMpi();

// MPI_Init_thread on construction (funneled), MPI_Finalize on destruction.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

}  // namespace sm::comp
