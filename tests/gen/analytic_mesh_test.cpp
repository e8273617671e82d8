#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "common/error.h"
#include "gen/generate.h"
#include "gen/mesh_checks.h"

namespace sm::gen {
namespace {

using mesh::CellType;
using test::matchFaces;

// Every boundary face of a cube mesh lies in one of the cube's six planes; returns their area.
double cubeBoundaryArea(const mesh::UnstructuredMesh& m, const test::FaceReport& r, double size) {
  double area = 0;
  for (const auto& f : r.boundaryFaces) {
    bool onPlane = false;
    for (int axis = 0; axis < 3; ++axis)
      for (double side : {0.0, size}) {
        bool all = true;
        for (int k = 0; k < f.size; ++k) all &= std::abs(m.points[f.ids[k]][axis] - side) < 1e-12;
        onPlane |= all;
      }
    EXPECT_TRUE(onPlane) << "a boundary face inside the cube: the split is not conforming";
    const glm::dvec3 p0 = m.points[f.ids[0]];
    for (int k = 1; k + 1 < f.size; ++k)
      area += 0.5 * glm::length(glm::cross(m.points[f.ids[k]] - p0, m.points[f.ids[k + 1]] - p0));
  }
  return area;
}

TEST(AnalyticMesh, SingleElementsAreUnitSizedAndPositive) {
  const double volume[4] = {1.0 / 6, 1.0 / 3, 0.5, 1.0};
  for (CellType t : mesh::kAllCellTypes) {
    auto m = singleElement(t);
    EXPECT_EQ(m.numCells(), 1u);
    EXPECT_EQ(m.numCells(t), 1u);
    EXPECT_EQ(m.numClusters(), 1);
    EXPECT_EQ(m.invertedFixed, 0u);
    EXPECT_NEAR(test::totalVolume(m), volume[mesh::typeIndex(t)], 1e-12) << mesh::cellTypeName(t);
    EXPECT_GT(test::minScaledJacobian(m), 0.3) << mesh::cellTypeName(t);
    auto b = m.bounds();
    EXPECT_EQ(b.lo, glm::dvec3(0.0));
    EXPECT_EQ(b.hi, glm::dvec3(1.0));
  }
}

TEST(AnalyticMesh, ZooSharesFacesConformingly) {
  auto m = zoo();
  for (CellType t : mesh::kAllCellTypes) EXPECT_GE(m.numCells(t), 1u) << mesh::cellTypeName(t);
  EXPECT_EQ(m.invertedFixed, 0u);
  auto r = matchFaces(m);
  EXPECT_EQ(r.overShared, 0u);
  EXPECT_EQ(r.sameWinding, 0u);
  // hexahedron-wedge, hexahedron-pyramid, two pyramid-tetrahedron and one wedge-tetrahedron faces.
  EXPECT_EQ(r.interior, 5u);
  auto surface = test::analyseSurface(r.boundaryFaces);
  EXPECT_EQ(surface.components, 1);
  EXPECT_TRUE(surface.closedAndOriented);
  // 1 (cube) + 1/4 (wedge) + 1/6 (pyramid) + 0.075 + 1/15 + 1/24 (tetrahedra).
  EXPECT_NEAR(test::totalVolume(m), 1.6, 1e-12);
  EXPECT_GT(test::minScaledJacobian(m), 0.05);
}

struct SplitCase {
  CubeSplit split;
  CellType type;
  uint64_t perCell;
};

class CubeSplitTest : public testing::TestWithParam<SplitCase> {};

TEST_P(CubeSplitTest, FillsTheCubeConformingly) {
  const SplitCase c = GetParam();
  for (int n : {1, 2, 3}) {
    const double size = 2.0;
    auto m = cube(c.split, n, size);
    EXPECT_EQ(m.numCells(c.type), c.perCell * n * n * n);
    EXPECT_EQ(cellsPerCube(c.split), c.perCell);
    EXPECT_EQ(m.numCells(), m.numCells(c.type));
    EXPECT_EQ(m.invertedFixed, 0u);
    EXPECT_NEAR(test::totalVolume(m), size * size * size, 1e-9);
    EXPECT_GT(test::minScaledJacobian(m), 0.3);
    auto r = matchFaces(m);
    EXPECT_EQ(r.overShared, 0u);
    EXPECT_EQ(r.sameWinding, 0u);
    EXPECT_NEAR(cubeBoundaryArea(m, r, size), 6 * size * size, 1e-9) << "n = " << n;
    auto surface = test::analyseSurface(r.boundaryFaces);
    EXPECT_EQ(surface.components, 1);
    EXPECT_TRUE(surface.closedAndOriented);
  }
}

INSTANTIATE_TEST_SUITE_P(AllSplits, CubeSplitTest,
                         testing::Values(SplitCase{CubeSplit::Tets5, CellType::Tet, 5},
                                         SplitCase{CubeSplit::Tets6, CellType::Tet, 6},
                                         SplitCase{CubeSplit::Wedges, CellType::Wedge, 2},
                                         SplitCase{CubeSplit::Pyramids, CellType::Pyramid, 6},
                                         SplitCase{CubeSplit::Hex, CellType::Hex, 1}));

TEST(AnalyticMesh, CubeIsDeterministicAndRejectsBadSizes) {
  auto a = cube(CubeSplit::Tets5, 3), b = cube(CubeSplit::Tets5, 3);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.cells, b.cells);
  EXPECT_THROW(cube(CubeSplit::Hex, 0), Error);
  EXPECT_THROW(cube(CubeSplit::Hex, 2, -1.0), Error);
}

TEST(AnalyticMesh, CubeSplitsByTheirGenerateNames) {
  EXPECT_EQ(cubeSplitNamed("cube-tets5"), CubeSplit::Tets5);
  EXPECT_EQ(cubeSplitNamed("cube-tets6"), CubeSplit::Tets6);
  EXPECT_EQ(cubeSplitNamed("cube-wedges"), CubeSplit::Wedges);
  EXPECT_EQ(cubeSplitNamed("cube-pyramids"), CubeSplit::Pyramids);
  EXPECT_EQ(cubeSplitNamed("cube-hex"), CubeSplit::Hex);
  EXPECT_EQ(cubeSplitNamed("cube-foo"), std::nullopt);
  EXPECT_EQ(cubeSplitNamed("zoo"), std::nullopt);
}

}  // namespace
}  // namespace sm::gen
