// How shellmarch's errors reach Python: one rule for the whole module (docs/PYTHON.md, "Errors").
#pragma once

#include <pybind11/pybind11.h>

namespace sm::python {

// Registers the module's exception translator: a file that cannot be opened (sm::FileError naming
// a path that does not exist or cannot be read) raises OSError; every other user error (sm::Error,
// the in-situ library's Error, an option the parser refuses) raises ValueError with the CLI's
// one-line message; anything else keeps pybind11's mapping (RuntimeError, MemoryError).
void registerErrors(pybind11::module_& m);

}  // namespace sm::python
