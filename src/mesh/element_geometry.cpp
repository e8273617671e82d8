#include "mesh/element_geometry.h"

#include <utility>

#include <glm/geometric.hpp>

namespace sm::mesh {

double signedVolume(CellType t, std::span<const uint32_t> ids, std::span<const glm::dvec3> points) {
  const uint32_t nv = numVerts(t);
  glm::dvec3 c(0.0);
  for (uint32_t i = 0; i < nv; ++i) c += points[ids[i]];
  c /= double(nv);
  double vol6 = 0.0;
  auto tri = [&](uint32_t a, uint32_t b, uint32_t d) {
    glm::dvec3 pa = points[a] - c, pb = points[b] - c, pd = points[d] - c;
    vol6 += glm::dot(pa, glm::cross(pb, pd));
  };
  for (uint32_t f = 0; f < numFaces(t); ++f) {
    uint32_t a = ids[faceVert(t, f, 0)], b = ids[faceVert(t, f, 1)], d = ids[faceVert(t, f, 2)];
    if (faceSize(t, f) == 3) {
      tri(a, b, d);
    } else {
      uint32_t tv[6], other[2];
      gpu::smQuadSplit(a, b, d, ids[faceVert(t, f, 3)], tv, other);
      tri(tv[0], tv[1], tv[2]);
      tri(tv[3], tv[4], tv[5]);
    }
  }
  return vol6 / 6.0;
}

void mirrorElement(CellType t, std::span<uint32_t> ids) {
  switch (t) {
    case CellType::Tet:
      std::swap(ids[1], ids[2]);
      break;
    case CellType::Pyramid:
      std::swap(ids[1], ids[3]);
      break;
    case CellType::Wedge:
      std::swap(ids[1], ids[2]);
      std::swap(ids[4], ids[5]);
      break;
    case CellType::Hex:
      std::swap(ids[1], ids[3]);
      std::swap(ids[5], ids[7]);
      break;
  }
}

bool hasRepeatedVertex(CellType t, std::span<const uint32_t> ids) {
  const uint32_t nv = numVerts(t);
  for (uint32_t i = 0; i < nv; ++i)
    for (uint32_t j = i + 1; j < nv; ++j)
      if (ids[i] == ids[j]) return true;
  return false;
}

}  // namespace sm::mesh
