// Whether a later step of a time series holds step 0's mesh. A series is rendered on the mesh of
// its first file (prepared, shelled and uploaded once), so a step whose points moved (a moving or
// deforming mesh, or one renumbered between steps with the same counts) would draw its values at
// step 0's positions, and a step whose cells join other points (remeshed with the same counts, or
// cells renumbered) would put its cell data on other cells: wrong images with no error. Counts
// alone (checked from the headers when the series is listed) catch neither; the points and cells
// themselves, read when a step's values are read, do.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "io/mesh_io.h"
#include "io/series.h"

namespace sm::mesh {
struct UnstructuredMesh;
}

namespace sm::io {

// A step's cells in file order, each as its VTK type and point ids (as the file numbers them, per
// piece): cell c is types[c] with ids[ends[c - 1] .. ends[c]).
struct StepCells {
  std::vector<int64_t> types, ends, ids;
};

// The mesh a step file holds, in file order: every piece of a .vtu, the pieces `options` choose
// of a .pvtu (in order), or the whole file read as readMesh reads it (its elements type by type).
struct StepMesh {
  std::vector<glm::dvec3> points;
  StepCells cells;
  // (file, points) and (file, cells) per piece read, for naming a point or cell in a message.
  std::vector<std::pair<std::string, uint64_t>> pointPieces, cellPieces;
};
StepMesh readStepMesh(const std::string& file, const ReadOptions& options);

// A mesh read whole, as a StepMesh (its elements type by type, as VTK cells).
StepMesh stepMeshOf(const mesh::UnstructuredMesh& m);

// The first index at which the two differ as positions (-0 and +0 alike), or none.
std::optional<uint64_t> firstMovedPoint(const std::vector<glm::dvec3>& first,
                                        const std::vector<glm::dvec3>& later);

// The first cell whose type or point ids differ, or none.
std::optional<uint64_t> firstChangedCell(const StepCells& first, const StepCells& later);

// Throws sm::FileError naming `path`, step k's file, the first point that moved (and both
// positions) or the first cell that changed (and both cells) when step k's mesh is not step 0's.
// Step 0's mesh is hashed once per process while its files are unchanged, so a stream of steps
// reads each later step's points and cells only.
void checkSameMesh(const std::string& path, const std::vector<SeriesStep>& steps, uint64_t k,
                   const ReadOptions& options);

// The same with step k's mesh already read (a file read whole, with its field).
void checkSameMesh(const std::string& path, const std::vector<SeriesStep>& steps, uint64_t k,
                   const ReadOptions& options, const StepMesh& later);

// The same for two meshes in memory (formats read whole): `first` is step 0's.
void checkSameMesh(const std::string& path, uint64_t k, const SeriesStep& step,
                   const StepMesh& first, const StepMesh& later);

}  // namespace sm::io
