#include "gen/volume_assembly.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "common/check.h"
#include "mesh/mesh_builder.h"

namespace sm::gen {

using mesh::CellType;

uint32_t VolumeAssembly::addPoint(const glm::dvec3& p) {
  SM_CHECK_LT(points.size(), size_t(0xFFFFFFFFu));
  points.push_back(p);
  return uint32_t(points.size() - 1);
}

void VolumeAssembly::addCell(CellType type, std::span<const uint32_t> ids) {
  SM_CHECK_EQ(ids.size(), mesh::numVerts(type));
  auto& out = cells[mesh::typeIndex(type)];
  out.insert(out.end(), ids.begin(), ids.end());
}

mesh::UnstructuredMesh VolumeAssembly::build(const std::string& source) const {
  mesh::MeshBuilder builder(source);
  builder.setPoints(points);
  uint64_t fileCell = 0;
  for (CellType t : mesh::kAllCellTypes) {
    const uint32_t nv = mesh::numVerts(t);
    const auto& ids = cells[mesh::typeIndex(t)];
    builder.reserveCells(t, ids.size() / nv);
    std::array<int64_t, 8> wide{};
    for (size_t e = 0; e < ids.size(); e += nv) {
      for (uint32_t k = 0; k < nv; ++k) wide[k] = ids[e + k];
      builder.addCell(t, {wide.data(), nv}, fileCell++);
    }
  }
  return builder.finish();
}

std::vector<Triangle> capQuads(VolumeAssembly& a, const std::vector<Quad>& quads,
                               const std::vector<glm::dvec3>& inside, double heightFraction) {
  SM_CHECK_EQ(quads.size(), inside.size());
  std::vector<Triangle> sides;
  sides.reserve(4 * quads.size());
  for (size_t i = 0; i < quads.size(); ++i) {
    const Quad& q = quads[i];
    glm::dvec3 centre(0.0), normal(0.0);
    double edges = 0;
    for (int k = 0; k < 4; ++k) {
      const glm::dvec3 &p = a.points[q[k]], &n = a.points[q[(k + 1) % 4]];
      centre += 0.25 * p;
      normal += glm::cross(p, n);  // Newell: robust for a non-planar quad
      edges += 0.25 * glm::length(n - p);
    }
    normal = glm::normalize(normal);
    // VTK's pyramid winds its base counter-clockwise seen from the apex.
    const bool reversed = glm::dot(normal, centre - inside[i]) < 0;
    if (reversed) normal = -normal;
    const uint32_t apex = a.addPoint(centre + heightFraction * edges * normal);
    const uint32_t pyramid[5] = {q[0], q[reversed ? 3 : 1], q[2], q[reversed ? 1 : 3], apex};
    a.addCell(CellType::Pyramid, pyramid);
    for (int k = 0; k < 4; ++k) sides.push_back({q[k], q[(k + 1) % 4], apex});
  }
  return sides;
}

std::vector<Triangle> addHexBlock(VolumeAssembly& a, const glm::dvec3& lo, const glm::dvec3& hi,
                                  double size) {
  const glm::dvec3 extent = hi - lo;
  int n[3];
  for (int axis = 0; axis < 3; ++axis) n[axis] = std::max(2, int(std::lround(extent[axis] / size)));
  const uint32_t first = uint32_t(a.points.size());
  auto index = [&](int i, int j, int k) {
    return first + uint32_t(i + (n[0] + 1) * (j + (n[1] + 1) * k));
  };
  for (int k = 0; k <= n[2]; ++k)
    for (int j = 0; j <= n[1]; ++j)
      for (int i = 0; i <= n[0]; ++i)
        a.addPoint(lo + extent * glm::dvec3(double(i) / n[0], double(j) / n[1], double(k) / n[2]));
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const uint32_t hex[8] = {index(i, j, k),
                                 index(i + 1, j, k),
                                 index(i + 1, j + 1, k),
                                 index(i, j + 1, k),
                                 index(i, j, k + 1),
                                 index(i + 1, j, k + 1),
                                 index(i + 1, j + 1, k + 1),
                                 index(i, j + 1, k + 1)};
        a.addCell(CellType::Hex, hex);
      }
  // The block's boundary quads, each capped away from the block's centre.
  std::vector<Quad> quads;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side : {0, n[axis]})
      for (int b = 0; b < n[v]; ++b)
        for (int c = 0; c < n[u]; ++c) {
          auto at = [&](int du, int dv) {
            int ijk[3];
            ijk[axis] = side;
            ijk[u] = c + du;
            ijk[v] = b + dv;
            return index(ijk[0], ijk[1], ijk[2]);
          };
          quads.push_back({at(0, 0), at(1, 0), at(1, 1), at(0, 1)});
        }
  }
  const std::vector<glm::dvec3> centre(quads.size(), 0.5 * (lo + hi));
  return capQuads(a, quads, centre, 0.5);
}

}  // namespace sm::gen
