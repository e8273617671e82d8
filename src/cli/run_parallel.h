// Runs a command on every rank: under mpirun with MPI collectives and the compositor's MPI
// communicator, otherwise as one process. An error on any rank is printed (with its rank) and ends
// every rank, never a hang.
#pragma once

#include <functional>

#include "comm/communicator.h"

namespace sm::app {

void runParallel(const std::function<void(comm::Communicator&)>& body);

}  // namespace sm::app
