#include "mpi_comm.h"

#include <string>

#include "common/error.h"

#ifdef SHELLMARCH_HAVE_MPI4PY
#include <mpi4py/mpi4py.h>
#endif

namespace py = pybind11;

namespace sm::python {
namespace {

std::string ourLibrary() {
  char text[MPI_MAX_LIBRARY_VERSION_STRING];
  int length = 0;
  MPI_Get_library_version(text, &length);
  return std::string(text, size_t(length));
}

std::string firstLine(const std::string& s) {
  return s.substr(0, s.find('\n'));
}

}  // namespace

MPI_Comm communicator(const py::object& comm) {
#ifndef SHELLMARCH_HAVE_MPI4PY
  (void)comm;
  throw Error(
      "comm: this build of shellmarch has no mpi4py support (python3-mpi4py was not found "
      "when it was configured); pass comm=None for one process");
#else
  // The same MPI library, or the communicator's handle means nothing here (Open MPI's MPI_Comm is
  // a pointer, MPICH's an int): refused by the library's version line, which names both.
  const py::module_ mpi = py::module_::import("mpi4py.MPI");
  const std::string theirs = py::str(mpi.attr("Get_library_version")());
  if (firstLine(theirs) != firstLine(ourLibrary()))
    throw Error("comm: mpi4py uses another MPI library (", firstLine(theirs), ") than shellmarch (",
                firstLine(ourLibrary()), ")");
  if (import_mpi4py() < 0) throw py::error_already_set();
  if (!PyObject_TypeCheck(comm.ptr(), &PyMPIComm_Type))
    throw py::type_error("comm: expected an mpi4py communicator (mpi4py.MPI.Comm) or None, not " +
                         std::string(py::str(py::type::of(comm).attr("__name__"))));
  MPI_Comm* c = PyMPIComm_Get(comm.ptr());
  if (!c) throw py::error_already_set();
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  if (!initialised || finalised)
    throw Error("comm: MPI is ", finalised ? "finalised" : "not initialised",
                " (import mpi4py.MPI with its default rc.initialize = True)");
  if (*c == MPI_COMM_NULL) throw Error("comm: is MPI.COMM_NULL");
  int inter = 0;
  MPI_Comm_test_inter(*c, &inter);
  if (inter) throw Error("comm: an intercommunicator; pass an intracommunicator");
  return *c;
#endif
}

}  // namespace sm::python
