#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "prep/memory_report.h"
#include "prep/prepare.h"
#include "prep/vertex_order.h"
#include "support/test_meshes.h"

namespace sm::prep {
namespace {

glm::dvec3 pos(const PreparedRank& r, uint32_t v) {
  return {r.positions[3 * v], r.positions[3 * v + 1], r.positions[3 * v + 2]};
}

// On a convex domain every shell triangle's normal points away from the centre, and the shell's
// area is the domain's surface area.
void expectOutwardClosedShell(const PreparedRank& r, double size) {
  double area = 0;
  glm::dvec3 centre(0.0);  // positions are rebased to the mesh centre
  for (uint64_t i = 0; i < r.numShellTriangles(); ++i) {
    glm::dvec3 a = pos(r, r.shellIndices[3 * i]), b = pos(r, r.shellIndices[3 * i + 1]),
               c = pos(r, r.shellIndices[3 * i + 2]);
    glm::dvec3 n = glm::cross(b - a, c - a);
    area += 0.5 * glm::length(n);
    EXPECT_GT(glm::dot(n, (a + b + c) / 3.0 - centre), 0.0) << "triangle " << i << " faces inward";
  }
  EXPECT_NEAR(area, 6 * size * size, 1e-4);
}

TEST(Shell, HexGridShellIsOutwardAndClosed) {
  auto m = test::hexGrid(3, 2.0);
  auto r = prepareRank(m, makeGlobalFrame(m.bounds()), PrepOptions{}).rank;
  expectOutwardClosedShell(r, 2.0);
  // Compact mode keeps the fourth vertex of every quad's triangles.
  for (uint32_t o : r.shellOther) EXPECT_NE(o, ~0u);
}

TEST(Shell, TetGridShellIsOutwardAndClosed) {
  auto m = test::kuhnTetGrid(3, 1.0, glm::dvec3(1e6, -2e6, 3e6));
  auto r = prepareRank(m, makeGlobalFrame(m.bounds()), PrepOptions{}).rank;
  expectOutwardClosedShell(r, 1.0);
  for (uint32_t o : r.shellOther) EXPECT_EQ(o, ~0u);
  // Rebased: far-from-origin input lands near zero in float.
  for (float p : r.positions) EXPECT_LE(std::abs(p), 0.5f + 1e-6f);
}

// A closed shell: every edge has exactly one neighbour, and adjacency is symmetric and shares the
// edge.
TEST(Shell, AdjacencyIsSymmetricOnAClosedShell) {
  auto m = test::hexGrid(2);
  auto r = prepareRank(m, makeGlobalFrame(m.bounds()), PrepOptions{}).rank;
  ASSERT_EQ(r.shellAdjacency.size(), 3 * r.numShellTriangles());
  for (uint32_t t = 0; t < r.numShellTriangles(); ++t) {
    for (uint32_t k = 0; k < 3; ++k) {
      uint32_t n = r.shellAdjacency[3 * t + k];
      ASSERT_NE(n, ~0u);
      uint32_t a = r.shellIndices[3 * t + k], b = r.shellIndices[3 * t + (k + 1) % 3];
      int back = 0;
      for (uint32_t j = 0; j < 3; ++j) {
        if (r.shellAdjacency[3 * n + j] != t) continue;
        ++back;
        // Consistent winding: the neighbour lists the shared edge in the opposite direction.
        EXPECT_EQ(r.shellIndices[3 * n + j], b);
        EXPECT_EQ(r.shellIndices[3 * n + (j + 1) % 3], a);
      }
      EXPECT_EQ(back, 1);
    }
  }
}

TEST(Shell, TrianglesAreSortedByMortonCode) {
  auto m = test::kuhnTetGrid(4);
  auto r = prepareRank(m, makeGlobalFrame(m.bounds()), PrepOptions{}).rank;
  mesh::Bounds b;
  std::vector<glm::dvec3> c(r.numShellTriangles());
  for (size_t i = 0; i < c.size(); ++i) {
    c[i] = (pos(r, r.shellIndices[3 * i]) + pos(r, r.shellIndices[3 * i + 1]) +
            pos(r, r.shellIndices[3 * i + 2])) /
           3.0;
    b.extend(c[i]);
  }
  for (size_t i = 1; i < c.size(); ++i) EXPECT_LE(mortonCode(c[i - 1], b), mortonCode(c[i], b));
}

TEST(Shell, ClustersOnOneRankMergeIntoOneVolume) {
  auto m = test::kuhnTetGrid(4, 1.0, glm::dvec3(0.0), /*clusters=*/3);
  ASSERT_EQ(m.numClusters(), 3);
  auto r = prepareRank(m, makeGlobalFrame(m.bounds()), PrepOptions{}).rank;
  EXPECT_EQ(r.numShellTriangles(), uint64_t(12 * 4 * 4));  // only the outer boundary
}

TEST(MemoryReport, TetCompactionSavesThreeQuarters) {
  auto m = test::kuhnTetGrid(3);
  auto r = prepareRank(m, makeGlobalFrame(m.bounds()), PrepOptions{}).rank;
  auto rep = memoryReport(r);
  EXPECT_DOUBLE_EQ(rep.compactionSavings(), 0.75);
  EXPECT_EQ(rep.compactedElements, r.elementCount[0] * 4);
  EXPECT_EQ(rep.connectivity, r.elementCount[0] * 16);
  EXPECT_EQ(rep.preparedBytes(), rep.vertices + rep.connectivity + rep.shell +
                                     rep.compactedElements + rep.scalarsPerStep);
  EXPECT_NE(rep.table().find("compaction saves 75.00%"), std::string::npos) << rep.table();
}

TEST(MemoryReport, HexesDoNotCompact) {
  auto m = test::hexGrid(2);
  auto rep = memoryReport(prepareRank(m, makeGlobalFrame(m.bounds()), PrepOptions{}).rank);
  EXPECT_EQ(rep.compactionSavings(), 0.0);
}

}  // namespace
}  // namespace sm::prep
