// What one rank keeps for rendering (the paper's "Data Preparation"): rebased vertices in a global
// order, per-type elements (XOR-compacted and/or plain), one neighbour per element face, and the
// shell (faces with no neighbour on this rank) as triangles.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/bounds.h"
#include "mesh/cell_type.h"

namespace sm::prep {

// Frame all ranks agree on: positions are stored as float(p - origin), and vertices are numbered
// in a global order derived from position alone, so every rank splits a shared quad the same way
// and computes bit-identical crossing distances on shared faces (docs/DESIGN.md invariants 1, 2,
// 7).
struct GlobalFrame {
  glm::dvec3 origin{0.0};
  // Device coordinates are (p - origin) * scale, a power of two (exact): 1 for data sets of
  // ordinary size, otherwise what brings the largest side to [1, 2) (makeGlobalFrame).
  double scale = 1.0;
  mesh::Bounds bounds;  // of the whole mesh (all ranks); quantises the Morton key
};
GlobalFrame makeGlobalFrame(const mesh::Bounds& wholeMesh);

struct PrepOptions {
  bool compact = true;  // XOR-compacted elements (false: plain VTK-ordered ids)
};

struct PreparedRank {
  GlobalFrame frame;
  bool compact = true;
  // Vertex i of this rank is mesh vertex vertexSource[i]; positions are rebased float xyz.
  std::vector<float> positions;
  std::vector<uint32_t> vertexSource;
  // Per type: element records (XOR-compacted when `compact`, else plain VTK order), and one
  // neighbour reference (index << 2 | type, or SM_NO_NEIGHBOR) per face slot. Face slots are VTK
  // face numbers, except tetrahedra, whose slot k is the face opposite their k-th smallest vertex.
  std::array<std::vector<uint32_t>, mesh::kNumCellTypes> elements;
  std::array<std::vector<uint32_t>, mesh::kNumCellTypes> neighbors;
  std::array<uint64_t, mesh::kNumCellTypes> elementCount{};
  // Shell triangles, wound outward, sorted by the Morton code of their centroids (lavapipe builds
  // BVHs in triangle order). shellIndices: 3 vertex ids per triangle (the BLAS index buffer);
  // shellRefs: the element behind the triangle; shellOther (compact mode only): the fourth vertex
  // of the quad a triangle came from (so XOR decoding knows the whole entry face), or ~0u.
  std::vector<uint32_t> shellIndices;
  std::vector<uint32_t> shellRefs;
  std::vector<uint32_t> shellOther;
  std::vector<uint32_t> shellAdjacency;  // 3 per triangle (see shell.h)

  uint64_t numVertices() const { return vertexSource.size(); }
  uint64_t numElements() const;
  uint64_t numShellTriangles() const { return shellRefs.size(); }
  uint32_t typesPresent() const;  // bit t set when elements of type t exist
};

}  // namespace sm::prep
