// The in-memory mesh every reader produces and every later stage consumes (umesh style: plain
// arrays plus free functions). Element vertex ids are 32-bit (one rank's piece never needs more);
// every count is 64-bit.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/bounds.h"
#include "mesh/cell_type.h"

namespace sm::mesh {

// A named per-vertex scalar field with one or more time steps: steps[t][vertex].
struct Field {
  std::string name;
  std::vector<std::vector<float>> steps;
  uint64_t numSteps() const { return steps.size(); }
};

// Cell data asked for as a field: steps[t][type][i] is the value of element i of that type (the
// order of UnstructuredMesh::cells). Readers hand these over; readMesh averages them onto the
// points once every piece is joined (cellFieldsToPoints), so a mesh it returns has none.
struct CellField {
  std::string name;
  std::vector<std::array<std::vector<float>, kNumCellTypes>> steps;
};

struct Range {
  double lo = 0, hi = 0;
  bool empty = true;
  void extend(double v);
  void extend(const Range& r);
};

// Cells a reader met but does not render; they are counted and reported, never silently dropped.
struct SkippedCells {
  uint64_t surface = 0;       // triangles, quads, polygons (2D cells)
  uint64_t lineOrVertex = 0;  // 0D and 1D cells
  uint64_t polyhedra = 0;     // VTK_POLYHEDRON cells that could not be split (mesh/polyhedron.h)
  uint64_t other = 0;         // anything else (unknown or unsupported volume types)
  uint64_t quadraticReduced = 0;  // kept, reduced to their corner vertices
  uint64_t polyhedraSplit = 0;    // kept, split into tetrahedra
  uint64_t polyhedronTets = 0;    // the tetrahedra they became
  uint64_t totalSkipped() const { return surface + lineOrVertex + polyhedra + other; }
  void add(const SkippedCells& s);
};

struct UnstructuredMesh {
  std::string source;  // file the mesh came from, for messages
  std::vector<glm::dvec3> points;
  std::array<std::vector<uint32_t>, kNumCellTypes> cells;    // numVerts(type) ids per element
  std::array<std::vector<int32_t>, kNumCellTypes> clusters;  // cluster id per element
  std::vector<Field> fields;
  std::vector<double> timeValues;  // time of each step, when the file says
  // The file's cell data arrays (not ids, ghosts or cluster ids). They become fields only when
  // ReadOptions::fields names them (averaged onto the points); listed for info and messages.
  std::vector<std::string> cellArrays;
  std::vector<CellField> cellFields;  // cell data asked for as fields, until averaged (above)
  SkippedCells skipped;
  uint64_t invertedFixed = 0;
  // For meshes joined from pieces (.pvtu): point i is point pointOrigin[i] of the pieces read,
  // their points numbered one after another, so that a later time step can be read without the
  // points (io::readFieldStep). Empty where the points are the file's own, in its order.
  std::vector<uint32_t> pointOrigin;
  // Kept when a reader is asked (io::ReadOptions::cellOrigins), and for files with polyhedra (the
  // tetrahedra of one then count once at a point: cellUsesAtPoints): element i, counted type by
  // type in the order of `cells`, is cell cellOrigin[i] of the files read, their cells (skipped
  // ones included) numbered one after another; fileCells is how many there are. A later step of
  // cell data is then read without the cells (io::readCellFieldStep). Where origins were not asked
  // for and only some pieces of a .pvtu hold polyhedra, the other pieces' elements are numbered in
  // their order (io::weldPieces): cells still count once, but such origins are not file numbers.
  std::vector<uint32_t> cellOrigin;
  uint64_t fileCells = 0;

  uint64_t numPoints() const { return points.size(); }
  uint64_t numCells(CellType t) const { return cells[typeIndex(t)].size() / numVerts(t); }
  uint64_t numCells() const;
  int32_t numClusters() const;  // 1 + largest cluster id; 0 for an empty mesh
  // Of the points that elements use (empty without elements, so also once preparation has taken
  // the cells).
  Bounds bounds() const;
  const Field* findField(const std::string& name) const;
  uint64_t numSteps() const;  // most steps of any field
};

// 1 for each point that an element uses, 0 for the others.
std::vector<uint8_t> usedPoints(const UnstructuredMesh& m);

// Scalar range of one step of a field, over finite values only.
Range fieldRange(const Field& f, uint64_t step);
Range fieldRange(const Field& f);  // all steps

// Text to append to a message about a point field `name` ("NAME" or "NAME[k]") a mesh lacks:
// where NAME is one of its cell arrays (UnstructuredMesh::cellArrays), or no name is given and it
// has some, says that cell data is read only when named (ReadOptions::fields); else empty.
std::string cellArrayHint(const std::vector<std::string>& cellArrays, const std::string& name = {});

// Turns every cell field into a point field of the same name: a point's value is the mean of the
// values of the elements that use it (VTK's Cell Data to Point Data), NaN where none does. On a
// partitioned mesh this must see every part, or points on the border of two parts would take a
// different value in each: run it on the whole mesh, or build the means from the pieces below with
// the sums of the other parts added (app::cellDataToPointsOverRanks).
void cellFieldsToPoints(UnstructuredMesh& m);
// The pieces of cellFieldsToPoints. Per point: the number of elements that use it, and the sum of
// their values in step `step` of `f`; the mean is sums / uses (NaN where uses is 0).
// A polyhedron split into tetrahedra counts once at each of its points, like any other cell, when
// the mesh has its cell origins (readers keep them for files with polyhedra).
std::vector<double> cellUsesAtPoints(const UnstructuredMesh& m);
std::vector<double> cellSumsAtPoints(const UnstructuredMesh& m, const CellField& f, size_t step);
// The same with one value per element, in the order of `cells` (type by type), over `numPoints`
// points (a caller may have freed m's points: the cells suffice).
std::vector<double> cellSumsAtPoints(const UnstructuredMesh& m, std::span<const float> perElement,
                                     uint64_t numPoints);
std::vector<float> meansAtPoints(const std::vector<double>& sums, const std::vector<double>& uses);
// Cells with a non-finite value among per-element values whose origins are `origins` (parallel;
// empty: one cell per element): a polyhedron's tetrahedra, consecutive with one origin, are one
// cell, as warnings count cells of the file.
uint64_t nonFiniteCells(std::span<const float> perElement, std::span<const uint32_t> origins);

// The other way (VTK's Point Data to Cell Data): every point field becomes a cell field of the same
// name, each element taking the mean of its vertices' values. Test meshes use it to stand for a
// finite-volume solver's output.
void pointFieldsToCells(UnstructuredMesh& m);

// Appends `b` to `a` (vertex ids of b shifted); fields must match by name and step count.
void append(UnstructuredMesh& a, const UnstructuredMesh& b);

}  // namespace sm::mesh
