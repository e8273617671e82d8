// The compiled half of `import shellmarch` (_shellmarch): file renders, info and the in-situ
// Renderer, taking arrays the Python half has already shaped (python/shellmarch/). Rendering and
// reading run with the GIL released.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "common/error.h"
#include "common/parallel.h"
#include "errors.h"
#include "file_render.h"
#include "mesh_renderer.h"
#include "mpi_comm.h"

namespace py = pybind11;
namespace api = shellmarch::insitu;

namespace sm::python {
namespace {

py::array_t<uint8_t> toArray(int width, int height, const std::vector<uint8_t>& rgba) {
  py::array_t<uint8_t> a({py::ssize_t(height), py::ssize_t(width), py::ssize_t(4)});
  std::memcpy(a.mutable_data(), rgba.data(), rgba.size());
  return a;
}

// Arrays reach here C-contiguous and of the right type (the Python half converts what it may);
// these checks keep a direct caller of _shellmarch from reading past an array.
void checkContiguous(const py::array& a, const char* what) {
  if (!(a.flags() & py::array::c_style)) throw Error(what, ": the array must be C-contiguous");
}

std::span<const double> points(const py::array& a) {
  checkContiguous(a, "points");
  if (a.dtype().kind() != 'f' || a.itemsize() != 8 || a.ndim() != 2 || a.shape(1) != 3)
    throw Error("points: needs an (n, 3) float64 array");
  return {static_cast<const double*>(a.data()), size_t(a.size())};
}

api::IndexSpan ids(const std::optional<py::array>& a, const char* what, py::ssize_t perCell) {
  if (!a) return {};
  checkContiguous(*a, what);
  const char kind = a->dtype().kind();
  if ((kind != 'i' && kind != 'u') || (a->itemsize() != 4 && a->itemsize() != 8) ||
      a->ndim() != 2 || a->shape(1) != perCell)
    throw Error(what, ": needs an (m, ", perCell, ") array of 32- or 64-bit integers");
  const size_t n = size_t(a->size());
  const void* p = a->data();
  if (a->itemsize() == 4)
    return kind == 'i' ? api::IndexSpan(std::span(static_cast<const int32_t*>(p), n))
                       : api::IndexSpan(std::span(static_cast<const uint32_t*>(p), n));
  return kind == 'i' ? api::IndexSpan(std::span(static_cast<const int64_t*>(p), n))
                     : api::IndexSpan(std::span(static_cast<const uint64_t*>(p), n));
}

std::span<const float> values(const py::array& a, const std::string& name) {
  checkContiguous(a, name.c_str());
  if (a.dtype().kind() != 'f' || a.itemsize() != 4 || a.ndim() != 1)
    throw Error("field '", name, "': needs a one-dimensional float32 array");
  return {static_cast<const float*>(a.data()), size_t(a.size())};
}

// One render, mesh upload or field upload at a time in this process: the GIL is released while
// they run, and two Python threads must not drive the devices and their shared caches at once.
// Taken with the GIL released, so a thread waiting here holds up no other Python thread.
std::mutex& engine() {
  static std::mutex m;
  return m;
}

// Lavapipe starts a thread per core in every process unless told otherwise; the command line's
// rule (this process's share of the node), kept where the user chose nothing.
void shareTheNodeWithLavapipe() {
  if (!std::getenv("LP_NUM_THREADS"))
    setenv("LP_NUM_THREADS", std::to_string(hardwareThreads()).c_str(), 0);
}

}  // namespace
}  // namespace sm::python

PYBIND11_MODULE(_shellmarch, m) {
  using namespace sm::python;
  m.doc() = "shellmarch's compiled core; use the shellmarch package";
  registerErrors(m);
  shareTheNodeWithLavapipe();

  m.def(
      "render_file",
      [](const std::string& path, const std::vector<std::string>& args) {
        Frames f;
        {
          py::gil_scoped_release unlocked;
          std::lock_guard lock(engine());
          f = renderFile(path, args);
        }
        py::list frames;
        for (const auto& rgba : f.rgba) frames.append(toArray(f.width, f.height, rgba));
        return frames;
      },
      py::arg("path"), py::arg("args"),
      "Renders a mesh file as `shellmarch render PATH ARGS...`; a list of (h, w, 4) uint8 "
      "frames");
  m.def(
      "info_json",
      [](const std::string& path) {
        py::gil_scoped_release unlocked;
        return sm::app::infoJsonText(path);
      },
      py::arg("path"), "What `shellmarch info --json PATH` prints");

  py::class_<MeshRenderer>(m, "Renderer")
      .def(py::init([](py::object comm, const std::string& device, const std::string& tracer) {
             api::Options o;
             o.device = device;
             o.tracer = tracer;
             std::optional<MPI_Comm> c;
             if (!comm.is_none()) c = communicator(comm);
             py::gil_scoped_release unlocked;
             std::lock_guard lock(engine());
             return std::make_unique<MeshRenderer>(c, o);
           }),
           py::arg("comm") = py::none(), py::arg("device") = "", py::arg("tracer") = "auto")
      .def_property_readonly("rank", &MeshRenderer::rank)
      .def_property_readonly("ranks", &MeshRenderer::ranks)
      .def(
          "set_mesh",
          [](MeshRenderer& r, const py::array& pts, std::optional<py::array> tetra,
             std::optional<py::array> pyramid, std::optional<py::array> wedge,
             std::optional<py::array> hexahedron) {
            api::MeshView v;
            v.points = points(pts);
            v.tetrahedra = ids(tetra, "tetra", 4);
            v.pyramids = ids(pyramid, "pyramid", 5);
            v.wedges = ids(wedge, "wedge", 6);
            v.hexahedra = ids(hexahedron, "hexahedron", 8);
            py::gil_scoped_release unlocked;
            std::lock_guard lock(engine());
            r.setMesh(v);
          },
          py::arg("points"), py::arg("tetra") = py::none(), py::arg("pyramid") = py::none(),
          py::arg("wedge") = py::none(), py::arg("hexahedron") = py::none())
      .def(
          "set_field",
          [](MeshRenderer& r, const std::string& name, const py::array& a) {
            const std::span<const float> v = values(a, name);
            py::gil_scoped_release unlocked;
            std::lock_guard lock(engine());
            r.setField(name, v);
          },
          py::arg("name"), py::arg("values"))
      .def(
          "set_cell_field",
          [](MeshRenderer& r, const std::string& name, const py::array& a) {
            const std::span<const float> v = values(a, name);
            py::gil_scoped_release unlocked;
            std::lock_guard lock(engine());
            r.setCellField(name, v);
          },
          py::arg("name"), py::arg("values"))
      .def(
          "render",
          [](MeshRenderer& r, const std::vector<std::string>& args) -> py::object {
            std::optional<Image8> img;
            {
              py::gil_scoped_release unlocked;
              std::lock_guard lock(engine());
              img = r.render(args);
            }
            if (!img) return py::none();
            return toArray(img->width, img->height, img->rgba);
          },
          py::arg("args"))
      .def("stats", [](const MeshRenderer& r) {
        const api::Stats s = r.stats();
        py::dict d;
        d["device"] = s.deviceName;
        d["tracer"] = s.tracer;
        d["vertices"] = s.vertices;
        d["elements"] = s.elements;
        d["shell_triangles"] = s.shellTriangles;
        d["geometry_builds"] = s.geometryBuilds;
        d["scalar_uploads"] = s.scalarUploads;
        d["validation_errors"] = s.validationErrors;
        d["validation_warnings"] = s.validationWarnings;
        d["prepare_seconds"] = s.prepareSeconds;
        d["frame_ms"] = s.frameMs;
        return d;
      });
}
