// The MPI_Comm inside an mpi4py communicator, checked: mpi4py present, built against this
// module's MPI, MPI initialised, an intracommunicator that is not MPI_COMM_NULL.
#pragma once

#include <mpi.h>

#include <pybind11/pybind11.h>

namespace sm::python {

// Throws sm::Error (ValueError) or TypeError naming `comm` for anything else.
MPI_Comm communicator(const pybind11::object& comm);

}  // namespace sm::python
