// Meshes made by shellmarch itself: CFD-like meshes from gmsh (the demo data set and benchmarks)
// and tiny analytic meshes for tests. Every mesh is positively oriented and conforming.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "mesh/unstructured_mesh.h"

namespace sm::gen {

enum class Body { Capsule, Lander };

struct CfdMeshOptions {
  Body body = Body::Capsule;
  uint64_t targetElements = 300000;  // 10 thousand .. 10 million; the result is within ~25%
  int clusters = 8;                  // METIS parts (non-convex, interlocking)
  int steps = 1;                     // time steps of the analytic fields
  bool hexBlock = false;             // add a block of hexahedra in the wake
  uint64_t seed = 1;
  int threads = 1;  // gmsh threads (0 = all cores); 1 is bit-reproducible and no slower in gmsh 4.8
};

// A body in a far-field box: boundary-layer wedges (prisms) on the body, hexahedra in the layer on
// the quad-meshed part of the wall (the capsule's afterbody cone, the lander's cylindrical side),
// pyramids joining those layer quads (and the hexahedral block's faces) to the tetrahedra,
// tetrahedra elsewhere, optionally a hexahedral block in the wake; split into clusters by METIS;
// analytic point fields (see addAnalyticFields) over `steps` steps. The far-field box is
// [-6, rear + 14] x [-7, 7]^2 in units of the body radius; the flow runs along +x.
// The element count is within ~25% of the target from 10 thousand to 10 million (the lander has at
// least ~10 thousand: its legs and nozzles need a minimum resolution). With one thread the mesh is
// bit-identical between runs; with more, gmsh's parallel meshing may vary the tetrahedra slightly.
// Throws sm::Error for bad options and when gmsh fails three times at nearby sizes.
mesh::UnstructuredMesh generateCfdMesh(const CfdMeshOptions& options);

// Tiny analytic meshes for tests (unit-sized, positively oriented, one cluster).
mesh::UnstructuredMesh singleElement(mesh::CellType type);
// One element of each type sharing faces: a hexahedron, a wedge on one of its quads, a pyramid on
// another, and tetrahedra on the pyramid's and wedge's triangles.
mesh::UnstructuredMesh zoo();
enum class CubeSplit { Tets5, Tets6, Wedges, Pyramids, Hex };
// The cube [0, size]^3 as n^3 cells, each split as asked (Pyramids: six pyramids around the
// cell centre; Wedges: two wedges).
mesh::UnstructuredMesh cube(CubeSplit split, int n = 1, double size = 1.0);
// The split a name such as "cube-tets5" stands for (the names `generate --analytic` takes), if any.
std::optional<CubeSplit> cubeSplitNamed(const std::string& name);
// Cells of one cube cell split that way (1, 2, 5 or 6).
uint64_t cellsPerCube(CubeSplit split);

// Adds analytic point fields over `steps` time steps, t in [0, 1]:
//   "linear"  x + 2y + 3z (normalised to the bounds), the same every step;
//   "shock"   a smoothed planar shock moving through the domain;
//   "vortex"  a swirling vortex whose centre moves with time;
//   "density" a bow shock, shock layer and swaying wake around a unit body at the origin facing -x
//             (world units: made for the capsule and the lander).
void addAnalyticFields(mesh::UnstructuredMesh& mesh, int steps);
// The same normalised to `domain` instead of the mesh's own bounds (a piece of a larger mesh then
// takes the values the whole mesh would), on up to `threads` threads (0: all).
void addAnalyticFields(mesh::UnstructuredMesh& mesh, int steps, const mesh::Bounds& domain,
                       unsigned threads = 0);

}  // namespace sm::gen
