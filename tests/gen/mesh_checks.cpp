#include "gen/mesh_checks.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include <glm/geometric.hpp>

#include "mesh/element_geometry.h"

namespace sm::test {
namespace {

using mesh::CellType;

template <typename F>
void forEachElement(const mesh::UnstructuredMesh& m, F&& f) {
  for (CellType t : mesh::kAllCellTypes) {
    const uint32_t nv = mesh::numVerts(t);
    const auto& cells = m.cells[mesh::typeIndex(t)];
    for (size_t e = 0; e < cells.size(); e += nv) f(t, &cells[e]);
  }
}

// Corners of each type as (vertex, a, b, c): the edges to a, b, c form a right-handed frame in a
// positively oriented VTK element. Pyramid apexes have four edges and are left out.
std::vector<std::array<int, 4>> corners(CellType t) {
  switch (t) {
    case CellType::Tet:
      return {{0, 1, 2, 3}, {1, 2, 0, 3}, {2, 0, 1, 3}, {3, 0, 2, 1}};
    case CellType::Pyramid:
      return {{0, 1, 3, 4}, {1, 2, 0, 4}, {2, 3, 1, 4}, {3, 0, 2, 4}};
    case CellType::Wedge:
      return {{0, 2, 1, 3}, {1, 0, 2, 4}, {2, 1, 0, 5}, {3, 4, 5, 0}, {4, 5, 3, 1}, {5, 3, 4, 2}};
    case CellType::Hex:
      return {{0, 1, 3, 4}, {1, 2, 0, 5}, {2, 3, 1, 6}, {3, 0, 2, 7},
              {4, 7, 5, 0}, {5, 4, 6, 1}, {6, 5, 7, 2}, {7, 6, 4, 3}};
  }
  return {};
}

struct Occurrence {
  uint32_t successor, predecessor;  // of the smallest id, in the element's winding
};

}  // namespace

FaceReport matchFaces(const mesh::UnstructuredMesh& m) {
  std::map<std::array<uint32_t, 4>, std::vector<std::pair<MeshFace, Occurrence>>> faces;
  forEachElement(m, [&](CellType t, const uint32_t* v) {
    for (uint32_t f = 0; f < mesh::numFaces(t); ++f) {
      MeshFace face{{0, 0, 0, 0xFFFFFFFFu}, int(mesh::faceSize(t, f))};
      for (int k = 0; k < face.size; ++k) face.ids[k] = v[mesh::faceVert(t, f, k)];
      int lowest =
          int(std::min_element(face.ids.begin(), face.ids.begin() + face.size) - face.ids.begin());
      Occurrence o{face.ids[(lowest + 1) % face.size],
                   face.ids[(lowest + face.size - 1) % face.size]};
      std::array<uint32_t, 4> key = face.ids;  // a triangle's unused slot sorts last
      std::sort(key.begin(), key.end());
      faces[key].push_back({face, o});
    }
  });
  FaceReport r;
  for (const auto& [key, list] : faces) {
    if (list.size() == 1) {
      ++r.boundary;
      r.boundaryFaces.push_back(list[0].first);
    } else if (list.size() > 2) {
      ++r.overShared;
    } else if (list[0].second.successor == list[1].second.predecessor &&
               list[0].second.predecessor == list[1].second.successor) {
      ++r.interior;
    } else {
      ++r.sameWinding;
    }
  }
  return r;
}

double minScaledJacobian(const mesh::UnstructuredMesh& m, CellType type) {
  double worst = 1.0;
  const uint32_t nv = mesh::numVerts(type);
  const auto& cells = m.cells[mesh::typeIndex(type)];
  for (size_t e = 0; e < cells.size(); e += nv) {
    const uint32_t* v = &cells[e];
    for (const auto& c : corners(type)) {
      const glm::dvec3 o = m.points[v[c[0]]];
      const glm::dvec3 a = m.points[v[c[1]]] - o, b = m.points[v[c[2]]] - o,
                       d = m.points[v[c[3]]] - o;
      const double scale = glm::length(a) * glm::length(b) * glm::length(d);
      worst = std::min(worst, scale > 0 ? glm::dot(a, glm::cross(b, d)) / scale : -1.0);
    }
  }
  return worst;
}

double minScaledJacobian(const mesh::UnstructuredMesh& m) {
  double worst = 1.0;
  for (CellType t : mesh::kAllCellTypes) worst = std::min(worst, minScaledJacobian(m, t));
  return worst;
}

double totalVolume(const mesh::UnstructuredMesh& m) {
  double sum = 0;
  forEachElement(m, [&](CellType t, const uint32_t* v) {
    sum += mesh::signedVolume(t, {v, mesh::numVerts(t)}, m.points);
  });
  return sum;
}

SurfaceReport analyseSurface(const std::vector<MeshFace>& faces) {
  std::vector<int> parent(faces.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  // Directed edges: a closed, consistently wound surface uses every edge once in each direction.
  std::map<std::pair<uint32_t, uint32_t>, std::vector<int>> directed;
  for (int f = 0; f < int(faces.size()); ++f)
    for (int k = 0; k < faces[f].size; ++k)
      directed[{faces[f].ids[k], faces[f].ids[(k + 1) % faces[f].size]}].push_back(f);
  SurfaceReport r;
  r.closedAndOriented = true;
  for (const auto& [edge, list] : directed) {
    auto reverse = directed.find({edge.second, edge.first});
    if (list.size() != 1 || reverse == directed.end() || reverse->second.size() != 1) {
      r.closedAndOriented = false;
      continue;
    }
    parent[find(list[0])] = find(reverse->second[0]);
  }
  for (int f = 0; f < int(faces.size()); ++f) r.components += find(f) == f;
  return r;
}

}  // namespace sm::test
