// Known-answer checks of the shared cell table: on reference elements every face points outward,
// and every element's faces form a closed, consistently wound surface.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "mesh/cell_type.h"
#include "mesh/element_geometry.h"

namespace sm::mesh {
namespace {

// Reference elements in VTK order with positive orientation under the face table.
std::vector<glm::dvec3> referenceElement(CellType t) {
  switch (t) {
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

std::vector<uint32_t> iota(uint32_t n) {
  std::vector<uint32_t> v(n);
  for (uint32_t i = 0; i < n; ++i) v[i] = i;
  return v;
}

TEST(CellTable, FacesPointOutward) {
  for (CellType t : kAllCellTypes) {
    auto p = referenceElement(t);
    glm::dvec3 c(0.0);
    for (auto& q : p) c += q;
    c /= double(p.size());
    for (uint32_t f = 0; f < numFaces(t); ++f) {
      glm::dvec3 n(0.0), fc(0.0);
      uint32_t fs = faceSize(t, f);
      for (uint32_t k = 0; k < fs; ++k) {
        const auto& a = p[faceVert(t, f, k)];
        const auto& b = p[faceVert(t, f, (k + 1) % fs)];
        n += glm::cross(a, b);  // Newell's normal
        fc += a;
      }
      fc /= double(fs);
      EXPECT_GT(glm::dot(n, fc - c), 0.0) << cellTypeName(t) << " face " << f;
    }
  }
}

TEST(CellTable, SurfaceIsClosedAndConsistent) {
  for (CellType t : kAllCellTypes) {
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (uint32_t f = 0; f < numFaces(t); ++f) {
      uint32_t fs = faceSize(t, f);
      for (uint32_t k = 0; k < fs; ++k)
        directed[{faceVert(t, f, k), faceVert(t, f, (k + 1) % fs)}]++;
    }
    for (auto& [e, count] : directed) {
      EXPECT_EQ(count, 1) << cellTypeName(t) << " edge used twice in one direction";
      EXPECT_EQ(directed.count({e.second, e.first}), 1u) << cellTypeName(t) << " open edge";
    }
  }
}

TEST(CellTable, ReferenceVolumesArePositiveAndMirrorNegates) {
  const double expected[4] = {1.0 / 6.0, 1.0 / 3.0, 0.5, 1.0};
  for (CellType t : kAllCellTypes) {
    auto p = referenceElement(t);
    auto ids = iota(numVerts(t));
    EXPECT_NEAR(signedVolume(t, ids, p), expected[typeIndex(t)], 1e-12) << cellTypeName(t);
    mirrorElement(t, ids);
    EXPECT_NEAR(signedVolume(t, ids, p), -expected[typeIndex(t)], 1e-12) << cellTypeName(t);
  }
}

TEST(CellTable, QuadSplitUsesSmallestVertexAndKeepsCycle) {
  uint32_t t[6], other[2];
  gpu::smQuadSplit(7, 3, 9, 5, t, other);  // smallest is 3 (b): diagonal b-d
  EXPECT_EQ(t[0], 3u);
  EXPECT_EQ(other[0], 7u);
  // Both triangles are consecutive runs of the cycle (7, 3, 9, 5), completed by `other`.
  const uint32_t cycle[4] = {7, 3, 9, 5};
  for (int tri = 0; tri < 2; ++tri) {
    int start = -1;
    for (int i = 0; i < 4; ++i)
      if (cycle[i] == t[tri * 3]) start = i;
    ASSERT_GE(start, 0);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(t[tri * 3 + k], cycle[(start + k) % 4]);
    EXPECT_EQ(other[tri], cycle[(start + 3) % 4]);
  }
  // The same quad seen from the other side (reversed cycle) gets the same diagonal.
  uint32_t r[6], ro[2];
  gpu::smQuadSplit(5, 9, 3, 7, r, ro);
  auto diag = [](const uint32_t* tv, const uint32_t* o) {
    // the diagonal is the pair of vertices shared by both triangles
    std::vector<uint32_t> d;
    for (int i = 0; i < 3; ++i)
      for (int j = 3; j < 6; ++j)
        if (tv[i] == tv[j]) d.push_back(tv[i]);
    (void)o;
    std::sort(d.begin(), d.end());
    return d;
  };
  EXPECT_EQ(diag(t, other), diag(r, ro));
  EXPECT_EQ(diag(t, other), (std::vector<uint32_t>{3, 5}));
}

}  // namespace
}  // namespace sm::mesh
