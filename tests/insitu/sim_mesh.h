// Meshes as a simulation holds them (flat xyz, 64-bit ids per element type, its own vertex
// order), for feeding the in-situ API in tests.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/unstructured_mesh.h"
#include "shellmarch/insitu.h"

namespace sm::insitu::test {

struct SimMesh {
  std::vector<double> xyz;
  std::array<std::vector<int64_t>, 4> cells;  // tetrahedra, pyramids, wedges, hexahedra
  std::vector<int64_t> ids;                   // of a share: each vertex's number in the whole mesh

  // withIds: pass `ids` as MeshView::globalIds.
  shellmarch::insitu::MeshView view(bool withIds = false) const {
    shellmarch::insitu::MeshView v{xyz, cells[0], cells[1], cells[2], cells[3]};
    if (withIds) v.globalIds = ids;
    return v;
  }
  size_t vertices() const { return xyz.size() / 3; }
  glm::dvec3 point(size_t i) const { return {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}; }
  // A field given as a function of position, in this mesh's vertex order.
  std::vector<float> field(const std::function<float(glm::dvec3)>& f) const;
};

SimMesh simMesh(const mesh::UnstructuredMesh& m);
// The same mesh with its vertices in a pseudo-random order (and the ids following them).
SimMesh shuffled(const SimMesh& s, uint32_t seed);
// The elements of m whose centroid has lo <= x < hi, with only the vertices they use, renumbered:
// one rank's share of a partition into slabs.
SimMesh slab(const mesh::UnstructuredMesh& m, double lo, double hi);
// m with a baffle at x = `at`: the elements on its +x side get their own copies of the vertices
// on the plane (appended), so the two sides touch without being joined.
mesh::UnstructuredMesh baffled(const mesh::UnstructuredMesh& m, double at);
// The elements of m whose centroid has lo <= x < hi (slab), with their vertices' numbers in m.
SimMesh slabWithIds(const mesh::UnstructuredMesh& m, double lo, double hi);
// The elements of m dealt to `parts` ranks by a hash of their index, rank `part`'s share with only
// the vertices they use, renumbered: parts that interlock, meeting at faces, edges and vertices.
SimMesh dealt(const mesh::UnstructuredMesh& m, int part, int parts);
// One value per element of s (its types in order), from the element's centroid.
std::vector<float> cellField(const SimMesh& s, const std::function<float(glm::dvec3)>& f);

}  // namespace sm::insitu::test
