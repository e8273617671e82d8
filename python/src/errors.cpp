#include "errors.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <CLI/CLI.hpp>

#include "common/error.h"
#include "common/setting_error.h"
#include "session/setting_names.h"
#include "shellmarch/insitu.h"

namespace sm::python {
namespace {

// Whether `path` names something this process cannot read as a file: the error is then about the
// file system (OSError), not about what the file holds.
bool unreadable(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return true;
  std::ifstream f(path, std::ios::binary);
  return !f.good();
}

void raise(PyObject* type, const std::string& what) {
  PyErr_SetString(type, printableLine(what).c_str());
}

}  // namespace

void registerErrors(pybind11::module_& m) {
  (void)m;
  pybind11::register_local_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const SettingError& e) {  // named by its keyword argument
      raise(PyExc_ValueError, session::pythonMessage(e));
    } catch (const FileError& e) {
      raise(unreadable(e.file()) ? PyExc_OSError : PyExc_ValueError, e.what());
    } catch (const Error& e) {
      raise(PyExc_ValueError, e.what());
    } catch (const shellmarch::insitu::Error& e) {
      raise(PyExc_ValueError, e.what());
    } catch (const CLI::ParseError& e) {
      raise(PyExc_ValueError, e.what());
    }
  });
}

}  // namespace sm::python
