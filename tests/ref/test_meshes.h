// Small analytic meshes and known answers for the reference renderer's tests, built inline so
// that the oracle's tests depend on nothing but the mesh model.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/unstructured_mesh.h"
#include "ref/ray_element.h"

namespace sm::ref::test {

// How each cube cell is split: 5 tetrahedra (alternating so that face diagonals match), 6
// tetrahedra around the main diagonal, 2 wedges, 6 pyramids around the cell centre, 1 hexahedron.
enum class Split { Tets5, Tets6, Wedges, Pyramids, Hex };
inline constexpr std::array<Split, 5> kAllSplits = {Split::Tets5, Split::Tets6, Split::Wedges,
                                                    Split::Pyramids, Split::Hex};
std::string splitName(Split s);

using ClusterOf = std::function<int32_t(int i, int j, int k)>;

// The box [lo, lo + size]^3 as n^3 cells split as asked: conforming, every element positively
// oriented, cluster of each element from its cell (i, j, k) (default 0).
mesh::UnstructuredMesh cubeMesh(Split split, int n, double size = 1.0,
                                const glm::dvec3& lo = glm::dvec3(0.0),
                                const ClusterOf& cluster = {});

// Unit reference elements in VTK order, positively oriented under the face table.
std::vector<glm::dvec3> referenceCorners(mesh::CellType type);

// A mesh of one element with the given corners (taken as given: no orientation fix).
mesh::UnstructuredMesh singleElement(mesh::CellType type, const std::vector<glm::dvec3>& corners);

// f evaluated at every point of the mesh.
std::vector<float> pointField(const mesh::UnstructuredMesh& m,
                              const std::function<double(const glm::dvec3&)>& f);

// The half-line's interval inside the box [lo, hi] (t >= 0), by the slab method; tIn > tOut when
// it misses.
Interval slab(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& origin,
              const glm::dvec3& dir);

}  // namespace sm::ref::test
