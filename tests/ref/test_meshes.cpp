#include "test_meshes.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mesh/element_geometry.h"

namespace sm::ref::test {

using mesh::CellType;

namespace {

struct Cell {
  std::array<uint32_t, 8> c;  // corner b at (i + (b & 1), j + (b >> 1 & 1), k + (b >> 2 & 1))
  uint32_t centre;            // cell-centre point (pyramid splits only)
  bool odd;                   // (i + j + k) odd
};

void addElement(mesh::UnstructuredMesh& m, CellType type, std::vector<uint32_t> ids,
                int32_t cluster) {
  if (mesh::signedVolume(type, ids, m.points) < 0.0) mesh::mirrorElement(type, ids);
  auto& cells = m.cells[mesh::typeIndex(type)];
  cells.insert(cells.end(), ids.begin(), ids.end());
  m.clusters[mesh::typeIndex(type)].push_back(cluster);
}

void splitCell(mesh::UnstructuredMesh& m, Split split, const Cell& cell, int32_t cluster) {
  const auto& c = cell.c;
  switch (split) {
    case Split::Hex:
      addElement(m, CellType::Hex, {c[0], c[1], c[3], c[2], c[4], c[5], c[7], c[6]}, cluster);
      break;
    case Split::Tets6: {  // paths 0 -> 0 + e_a -> 0 + e_a + e_b -> 7 for every axis order
      const int axes[6][2] = {{1, 2}, {1, 4}, {2, 1}, {2, 4}, {4, 1}, {4, 2}};
      for (const auto& a : axes)
        addElement(m, CellType::Tet, {c[0], c[a[0]], c[a[0] | a[1]], c[7]}, cluster);
      break;
    }
    case Split::Tets5: {  // corner tetrahedra at one parity class, the central one at the other
      const int corners[2][4] = {{1, 2, 4, 7}, {0, 3, 5, 6}};
      const auto& cs = corners[cell.odd];
      for (int b : cs) addElement(m, CellType::Tet, {c[b], c[b ^ 1], c[b ^ 2], c[b ^ 4]}, cluster);
      const auto& mid = corners[!cell.odd];
      addElement(m, CellType::Tet, {c[mid[0]], c[mid[1]], c[mid[2]], c[mid[3]]}, cluster);
      break;
    }
    case Split::Wedges:
      addElement(m, CellType::Wedge, {c[0], c[1], c[3], c[4], c[5], c[7]}, cluster);
      addElement(m, CellType::Wedge, {c[0], c[3], c[2], c[4], c[7], c[6]}, cluster);
      break;
    case Split::Pyramids: {
      const int faces[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                               {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
      for (const auto& f : faces)
        addElement(m, CellType::Pyramid, {c[f[0]], c[f[1]], c[f[2]], c[f[3]], cell.centre},
                   cluster);
      break;
    }
  }
}

}  // namespace

std::string splitName(Split s) {
  switch (s) {
    case Split::Tets5:
      return "tets5";
    case Split::Tets6:
      return "tets6";
    case Split::Wedges:
      return "wedges";
    case Split::Pyramids:
      return "pyramids";
    case Split::Hex:
      return "hex";
  }
  return "?";
}

mesh::UnstructuredMesh cubeMesh(Split split, int n, double size, const glm::dvec3& lo,
                                const ClusterOf& cluster) {
  mesh::UnstructuredMesh m;
  m.source = "cube-" + splitName(split);
  const int np = n + 1;
  auto grid = [&](int i, int j, int k) { return uint32_t(i + np * (j + np * k)); };
  for (int k = 0; k < np; ++k)
    for (int j = 0; j < np; ++j)
      for (int i = 0; i < np; ++i) m.points.push_back(lo + size * glm::dvec3(i, j, k) / double(n));
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        Cell cell;
        for (int b = 0; b < 8; ++b)
          cell.c[b] = grid(i + (b & 1), j + (b >> 1 & 1), k + (b >> 2 & 1));
        cell.odd = (i + j + k) % 2 == 1;
        cell.centre = uint32_t(m.points.size());
        if (split == Split::Pyramids)
          m.points.push_back(lo + size * (glm::dvec3(i, j, k) + 0.5) / double(n));
        splitCell(m, split, cell, cluster ? cluster(i, j, k) : 0);
      }
  return m;
}

std::vector<glm::dvec3> referenceCorners(CellType type) {
  switch (type) {
    case CellType::Tet:
      return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    case CellType::Pyramid:
      return {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}};
    case CellType::Wedge:
      return {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {0, 1, 1}, {1, 0, 1}};
    case CellType::Hex:
      return {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
              {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  }
  return {};
}

mesh::UnstructuredMesh singleElement(CellType type, const std::vector<glm::dvec3>& corners) {
  mesh::UnstructuredMesh m;
  m.source = "single-element";
  m.points = corners;
  for (uint32_t i = 0; i < corners.size(); ++i) m.cells[mesh::typeIndex(type)].push_back(i);
  m.clusters[mesh::typeIndex(type)].push_back(0);
  return m;
}

std::vector<float> pointField(const mesh::UnstructuredMesh& m,
                              const std::function<double(const glm::dvec3&)>& f) {
  std::vector<float> v;
  for (const auto& p : m.points) v.push_back(float(f(p)));
  return v;
}

Interval slab(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& origin,
              const glm::dvec3& dir) {
  double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (dir[a] == 0.0) {
      if (origin[a] < lo[a] || origin[a] > hi[a]) return {1.0, 0.0};
      continue;
    }
    double ta = (lo[a] - origin[a]) / dir[a], tb = (hi[a] - origin[a]) / dir[a];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  return {t0, t1};
}

}  // namespace sm::ref::test
