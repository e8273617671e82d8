// One cluster of the grid mesh as its own mesh: the cells it holds split into elements, the points
// they use numbered in first-use order, and the analytic fields at those points.
#include <array>
#include <cmath>
#include <span>

#include "common/check.h"
#include "gen/generate.h"
#include "gen/grid_mesh.h"
#include "mesh/element_geometry.h"

namespace sm::gen {
namespace {

using mesh::CellType;
constexpr uint8_t kCentre = 8;  // corner index of a transition cell's centre point

// An element as corners of its grid cell: corner b has offsets (b & 1, b >> 1 & 1, b >> 2 & 1)
// along (radius, theta, z), a right-handed frame that the map to x, y, z keeps (its Jacobian
// determinant is r > 0); so orientation found on the unit cube holds in every cell.
struct Element {
  CellType type;
  std::array<uint8_t, 8> corners;
};

Element oriented(CellType type, std::initializer_list<uint8_t> corners) {
  Element e{type, {}};
  std::copy(corners.begin(), corners.end(), e.corners.begin());
  std::array<glm::dvec3, 9> unit;
  for (uint32_t b = 0; b < 8; ++b) unit[b] = glm::dvec3(b & 1, b >> 1 & 1, b >> 2 & 1);
  unit[kCentre] = glm::dvec3(0.5);
  std::array<uint32_t, 8> ids{};
  const uint32_t n = mesh::numVerts(type);
  for (uint32_t v = 0; v < n; ++v) ids[v] = e.corners[v];
  std::span<uint32_t> span(ids.data(), n);
  if (mesh::signedVolume(type, span, unit) < 0.0) mesh::mirrorElement(type, span);
  for (uint32_t v = 0; v < n; ++v) e.corners[v] = uint8_t(ids[v]);
  return e;
}

// Every face diagonal runs from the face's lowest corner to its highest (Kuhn's split does so), so
// wedges, tetrahedra and transition cells all agree on the faces they share.
struct Templates {
  std::vector<Element> wedges, hex, tets, transition;
  Templates() {
    wedges = {oriented(CellType::Wedge, {0, 2, 6, 1, 3, 7}),
              oriented(CellType::Wedge, {0, 6, 4, 1, 7, 5})};
    hex = {oriented(CellType::Hex, {0, 1, 3, 2, 4, 5, 7, 6})};
    for (auto [a, b] : {std::pair{0, 1}, {0, 2}, {1, 0}, {1, 2}, {2, 0}, {2, 1}})
      tets.push_back(
          oriented(CellType::Tet, {0, uint8_t(1u << a), uint8_t((1u << a) | (1u << b)), 7}));
    // The face at the wall side (radius offset 0) is the hexahedron's quad: a pyramid; the other
    // five faces are cut in two triangles, each a tetrahedron with the centre.
    transition = {oriented(CellType::Pyramid, {0, 2, 6, 4, kCentre})};
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        if (axis == 0 && side == 0) continue;
        const int u = (axis + 1) % 3, w = (axis + 2) % 3;
        const uint8_t base = uint8_t(side << axis);
        const uint8_t q0 = base, q1 = uint8_t(base | 1 << u), q3 = uint8_t(base | 1 << w);
        const uint8_t q2 = uint8_t(q1 | q3);
        transition.push_back(oriented(CellType::Tet, {q0, q1, q2, kCentre}));
        transition.push_back(oriented(CellType::Tet, {q0, q2, q3, kCentre}));
      }
  }
  const std::vector<Element>& of(GridCell kind) const {
    switch (kind) {
      case GridCell::Wedges:
        return wedges;
      case GridCell::Hex:
        return hex;
      case GridCell::Transition:
        return transition;
      case GridCell::Tets:
        break;
    }
    return tets;
  }
};

// Local ids of grid nodes over the boxes a piece's cells come from. A node in several boxes'
// ranges takes the first box's slot, so it gets one id whichever cell reaches it.
class NodeIds {
 public:
  NodeIds(const std::vector<GridMesh::Box>& boxes, int nTheta) : boxes_(boxes), nTheta_(nTheta) {
    for (const GridMesh::Box& b : boxes) {
      const Extent e{b.j1 - b.j0 + 2, std::min(b.i1 - b.i0 + 2, nTheta), b.k1 - b.k0 + 2};
      extents_.push_back(e);
      ids_.emplace_back(size_t(e.j) * e.i * e.k, ~0u);
    }
  }
  uint32_t& operator()(int j, int i, int k) {
    for (size_t b = 0; b < boxes_.size(); ++b) {
      const GridMesh::Box& x = boxes_[b];
      const Extent& e = extents_[b];
      const int dj = j - x.j0, di = ((i - x.i0) % nTheta_ + nTheta_) % nTheta_, dk = k - x.k0;
      if (dj >= 0 && dj < e.j && di < e.i && dk >= 0 && dk < e.k)
        return ids_[b][(size_t(dk) * e.j + dj) * e.i + di];
    }
    SM_CHECK(false);
    return ids_[0][0];
  }

 private:
  struct Extent {
    int j, i, k;
  };
  std::vector<GridMesh::Box> boxes_;
  std::vector<Extent> extents_;
  std::vector<std::vector<uint32_t>> ids_;
  int nTheta_;
};

}  // namespace

// Growing the arrays element by element would copy each several times (a tenth of the time).
void GridMesh::reserve(mesh::UnstructuredMesh& m, const std::vector<Box>& boxes) const {
  uint64_t boxCells = 0;
  for (const Box& b : boxes)
    boxCells += uint64_t(b.j1 - b.j0 + 1) * (b.i1 - b.i0 + 1) * (b.k1 - b.k0 + 1);
  const int bands = nested_ >= 0 ? clusters_ - 1 : clusters_;
  const double cells =
      std::min(double(boxCells), 1.1 * double(nTheta_) * radialCells() * nZ_ / bands);
  const double share = cells / (double(nTheta_) * radialCells() * nZ_);
  for (mesh::CellType t : mesh::kAllCellTypes) {
    const uint32_t ti = mesh::typeIndex(t);
    m.cells[ti].reserve(size_t(share * double(typeCounts_[ti]) * 1.05) * mesh::numVerts(t));
    m.clusters[ti].reserve(size_t(share * double(typeCounts_[ti]) * 1.05));
  }
  m.points.reserve(size_t(share * double(points()) * 1.2));
}

mesh::UnstructuredMesh GridMesh::piece(int cluster) const {
  static const Templates templates;
  SM_CHECK(cluster >= 0 && cluster < clusters_);
  const std::vector<Box> boxes = candidateBoxes(cluster);
  NodeIds ids(boxes, nTheta_);
  mesh::UnstructuredMesh m;
  m.source = "grid mesh";
  auto nodeId = [&](int j, int i, int k) {
    uint32_t& id = ids(j, i, k);
    if (id == ~0u) {
      id = uint32_t(m.points.size());
      m.points.push_back(node(j, i, k));
    }
    return id;
  };
  reserve(m, boxes);
  std::array<uint32_t, 9> corner{};
  for (size_t b = 0; b < boxes.size(); ++b) {
    const Box& box = boxes[b];
    for (int k = box.k0; k <= box.k1; ++k)
      for (int j = box.j0; j <= box.j1; ++j)
        for (int ii = box.i0; ii <= box.i1; ++ii) {
          const int i = (ii % nTheta_ + nTheta_) % nTheta_;
          bool seen = false;  // in an earlier box: made there
          for (size_t a = 0; a < b; ++a) seen = seen || boxes[a].holds(j, i, k, nTheta_);
          if (seen || clusterOfCell(j, i, k) != cluster) continue;
          for (uint32_t c = 0; c < 8; ++c)
            corner[c] = nodeId(j + int(c & 1), ii + int(c >> 1 & 1), k + int(c >> 2 & 1));
          const GridCell kind = cellKind(j, i);
          if (kind == GridCell::Transition) {
            corner[kCentre] = uint32_t(m.points.size());
            m.points.push_back(cellCentre(j, i, k));
          }
          for (const Element& e : templates.of(kind)) {
            const uint32_t t = mesh::typeIndex(e.type);
            for (uint32_t v = 0; v < mesh::numVerts(e.type); ++v)
              m.cells[t].push_back(corner[e.corners[v]]);
            m.clusters[t].push_back(cluster);
          }
        }
  }
  addAnalyticFields(m, steps_, bounds(), 1);
  return m;
}

}  // namespace sm::gen
