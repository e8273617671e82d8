// The one place where cells enter a mesh. Every reader hands its cells here, so validation
// (ids in range, repeated vertices, finite coordinates), orientation fixing, quadratic-cell
// reduction and the counting of skipped cells happen identically for every format, with messages
// naming the file and the file's own cell number.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/polyhedron.h"
#include "mesh/unstructured_mesh.h"

namespace sm::mesh {

// Element vertex ids are 32-bit (UnstructuredMesh::cells), so one mesh, and so one rank's share,
// holds at most this many points.
inline constexpr uint64_t kMaxMeshPoints = 0xFFFFFFFFull;
// Refuses `points` past kMaxMeshPoints with one sm::FileError naming `source`: "<holder> N points:
// vertex ids are 32-bit, ... (<fits>)". Readers call it with the count a header declares, before
// anything of that size is read; `fits` says what would fit ("use more ranks").
void checkPointCount(const std::string& source, uint64_t points, std::string_view holder,
                     std::string_view fits);

class MeshBuilder {
 public:
  explicit MeshBuilder(std::string source);

  // Points must be set before cells (orientation needs them). Non-finite coordinates throw.
  void setPoints(std::vector<glm::dvec3> points);
  uint64_t numPoints() const { return mesh_.points.size(); }

  // A cell as VTK describes it. Volume cells are kept (quadratic and higher-order ones reduced to
  // their corners, voxels converted to hexahedra); 0D, 1D, 2D cells and polyhedra are counted and
  // skipped. Throws sm::FileError for ids out of range and repeated vertices.
  void addVtkCell(int vtkType, std::span<const int64_t> ids, uint64_t fileCell,
                  int32_t cluster = 0);
  // A polyhedron (VTK type 42) given by its faces, split into tetrahedra (mesh/polyhedron.h); one
  // that cannot be split is counted and skipped. Throws sm::FileError for ids out of range, faces
  // of fewer than 3 points and a point twice in one face.
  void addPolyhedron(const PolyhedronFaces& faces, uint64_t fileCell, int32_t cluster = 0);
  // A polyhedron skipped for `why` (its faces not even looked at: too large to copy).
  void skipPolyhedron(uint64_t fileCell, PolyhedronSplit why);
  // A linear cell in VTK vertex order (used by formats that are not VTK's, after their conversion).
  void addCell(CellType type, std::span<const int64_t> ids, uint64_t fileCell, int32_t cluster = 0);

  void reserveCells(CellType type, uint64_t n);

  // A point field step; values.size() must equal the point count. Non-finite values are allowed
  // (they render transparent) and reported once per field as a warning.
  void addFieldStep(const std::string& name, uint64_t step, std::vector<float> values);
  void setTimeValues(std::vector<double> times) { mesh_.timeValues = std::move(times); }
  void setCellArrays(std::vector<std::string> names) { mesh_.cellArrays = std::move(names); }
  // A step of cell data asked for as a field: one value per file cell (skipped cells included),
  // kept for the cells kept (UnstructuredMesh::cellFields).
  void addCellFieldStep(const std::string& name, uint64_t step, std::span<const float> perFileCell);
  // Replaces the cluster id of every cell added so far that came from file cell i with ids[i];
  // ids far above the cell count are renumbered densely, in order (renumberSparseClusters).
  void setClusterIds(std::span<const int64_t> perFileCell, const std::string& arrayName);

  // Makes finish() record each kept cell's file cell number (UnstructuredMesh::cellOrigin), the
  // file having `fileCells` cells in all.
  void keepCellOrigins(uint64_t fileCells);
  // The file's cell count, for readers not asked to keep origins: finish() then records them only
  // when a polyhedron was split (cellUsesAtPoints counts its tetrahedra once at a point).
  void setFileCells(uint64_t fileCells);

  // Checks fields for missing steps, prints one warning per kind of fix or skip, returns the mesh.
  UnstructuredMesh finish();

 private:
  void renumberSparseClusters(const std::string& arrayName);
  // Skipped and higher-order cells' ids must name points too (a file's damage shows there first).
  void checkPointIds(int vtkType, std::span<const int64_t> ids, uint64_t fileCell) const;

  std::string source_;
  UnstructuredMesh mesh_;
  // File cell number of every kept cell, per type, so that cell arrays (clusters) can be applied.
  std::array<std::vector<uint64_t>, kNumCellTypes> fileCellOf_;
  std::optional<uint64_t> fileCells_;  // set: keep the cells' origins
  bool keepOrigins_ = false;           // asked for, not only counted
  uint64_t firstInvertedCell_ = 0;
  uint64_t degenerate_ = 0;
  uint64_t firstUnsplitPolyhedron_ = 0;
  PolyhedronSplit firstUnsplitReason_ = PolyhedronSplit::Ok;
  std::vector<std::array<uint32_t, 4>> polyTets_;  // reused
  uint64_t firstDegenerateCell_ = 0;
};

}  // namespace sm::mesh
