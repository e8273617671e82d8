// shellmarch.Renderer and render(Mesh): the in-situ library's Renderer (libshellmarch_insitu)
// driven by the same render options as files (scene_args.h), its image composited as the PNG
// writer composites it.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mesh/unstructured_mesh.h"
#include "shellmarch/insitu.h"

namespace sm::python {

struct Image8 {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  // 8-bit RGBA rows, as scene::toRgba8
};

class MeshRenderer {
 public:
  // `comm`: collective over it (duplicated by the library); none: one process, no MPI calls.
  MeshRenderer(std::optional<MPI_Comm> comm, const shellmarch::insitu::Options& options);

  int rank() const { return renderer_->rank(); }
  int ranks() const { return renderer_->ranks(); }

  // Collective. Also agrees on the whole mesh's bounds (the CLI's camera frames them).
  void setMesh(const shellmarch::insitu::MeshView& mesh);
  // Local, as Renderer::setField; keeps the values' finite range for --opacity's table.
  void setField(const std::string& name, std::span<const float> values);
  // Collective, as Renderer::setCellField.
  void setCellField(const std::string& name, std::span<const float> values);
  // Collective. `args`: render options (parseSceneArgs); the image on rank 0, none elsewhere.
  std::optional<Image8> render(const std::vector<std::string>& args);

  shellmarch::insitu::Stats stats() const { return renderer_->stats(); }

 private:
  std::pair<double, double> opacityRange(const std::string& field);
  double reduce(double v, MPI_Op op);

  std::optional<MPI_Comm> comm_;
  std::unique_ptr<shellmarch::insitu::Renderer> renderer_;
  mesh::Bounds whole_;
  std::string firstField_;
  // Finite range of each point field on this rank; NaN for cell fields (averaged in the library).
  std::map<std::string, std::pair<double, double>> ranges_;
};

}  // namespace sm::python
