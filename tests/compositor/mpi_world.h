// What the MPI-aware test main sets up for the tests of one process: the world communicator and
// this process's Vulkan context (validation on under ctest).
#pragma once

#include "comm/mpi/mpi_communicator.h"
#include "vk/context.h"

namespace sm::comp::test {

comm::MpiCommunicator& mpiWorld();
const vk::Context& mpiContext();

}  // namespace sm::comp::test
