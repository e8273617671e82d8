// Small structured meshes built inline for module tests that must not depend on src/gen.
#pragma once

#include "mesh/unstructured_mesh.h"

namespace sm::test {

// n^3 hexahedra filling [0, size]^3 + offset; cluster of each cell = its x slab index % clusters.
mesh::UnstructuredMesh hexGrid(int n, double size = 1.0, glm::dvec3 offset = glm::dvec3(0.0),
                               int clusters = 1);
// The same grid with every cell split into 6 tetrahedra around its main diagonal (conforming).
mesh::UnstructuredMesh kuhnTetGrid(int n, double size = 1.0, glm::dvec3 offset = glm::dvec3(0.0),
                                   int clusters = 1);

// The grid with every cell split into two wedges (prisms along z, split by the xy diagonal 0-2).
mesh::UnstructuredMesh wedgeGrid(int n, double size = 1.0);
// The grid with every cell split into six pyramids around an added centre vertex.
mesh::UnstructuredMesh pyramidGrid(int n, double size = 1.0);

// A synthetic mesh of n^3 cube cells, each a hexahedron, two wedges, six tetrahedra or six
// pyramids around an extra centre point (all four types), in `clusters` slabs along x, with fields
// "f" (1 step) and "g" (2 steps) and time values 0 and 1.
mesh::UnstructuredMesh makeTestMesh(int n, int clusters);

// The mean of the vertices of element e of type index t.
glm::dvec3 cellCentroid(const mesh::UnstructuredMesh& m, int t, size_t e);

}  // namespace sm::test
