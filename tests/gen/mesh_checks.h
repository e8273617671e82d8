// Independent checks of a mesh's validity, shared by the generator and partition tests: face
// matching (conformity), corner Jacobians (no inverted or degenerate elements), volumes.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "mesh/unstructured_mesh.h"

namespace sm::test {

// An element face as its element winds it (outward for a positively oriented element).
struct MeshFace {
  std::array<uint32_t, 4> ids;  // ids[3] unused for triangles
  int size;
};

struct FaceReport {
  uint64_t interior = 0;     // faces shared by exactly two elements, wound oppositely
  uint64_t boundary = 0;     // faces of one element only
  uint64_t overShared = 0;   // faces listed by three or more elements
  uint64_t sameWinding = 0;  // faces shared by two elements that wind them the same way
  std::vector<MeshFace> boundaryFaces;
};
FaceReport matchFaces(const mesh::UnstructuredMesh& m);

// Smallest corner Jacobian over all elements, scaled by its three edge lengths (1 for a right
// corner, 0 for a flat one, negative for an inverted one).
double minScaledJacobian(const mesh::UnstructuredMesh& m);
double minScaledJacobian(const mesh::UnstructuredMesh& m, mesh::CellType type);

double totalVolume(const mesh::UnstructuredMesh& m);

// Connected components of a set of faces (linked through shared edges), and whether every edge of
// it is used by exactly two of its faces in opposite directions (closed and consistently wound).
struct SurfaceReport {
  int components = 0;
  bool closedAndOriented = false;
};
SurfaceReport analyseSurface(const std::vector<MeshFace>& faces);

}  // namespace sm::test
