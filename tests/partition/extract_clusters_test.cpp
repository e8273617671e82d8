#include <gtest/gtest.h>

#include <algorithm>

#include "gen/generate.h"
#include "gen/mesh_checks.h"
#include "partition/partition.h"

namespace sm::partition {
namespace {

using mesh::CellType;

mesh::UnstructuredMesh clusteredCube(int clusters) {
  auto m = gen::cube(gen::CubeSplit::Tets5, 6);
  gen::addAnalyticFields(m, 2);
  assignMetisClusters(m, clusters);
  return m;
}

// The elements of a mesh as sorted vertex tuples in the numbering of `original` points.
std::vector<std::vector<uint32_t>> elementTuples(const mesh::UnstructuredMesh& m,
                                                 const std::vector<uint32_t>& toOriginal) {
  std::vector<std::vector<uint32_t>> out;
  for (CellType t : mesh::kAllCellTypes) {
    const uint32_t nv = mesh::numVerts(t);
    const auto& ids = m.cells[mesh::typeIndex(t)];
    for (size_t e = 0; e < ids.size(); e += nv) {
      std::vector<uint32_t> tuple{uint32_t(mesh::typeIndex(t))};
      for (uint32_t k = 0; k < nv; ++k) tuple.push_back(toOriginal[ids[e + k]]);
      out.push_back(tuple);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Points no element uses (a quadratic cell's mid-edge nodes) come along with keepUnusedPoints, in
// their place in point order and with their field values, so that the one share taking them keeps
// the whole mesh's field ranges; without it they are left out.
TEST(ExtractClusters, KeepsThePointsNoElementUsesWhenAsked) {
  auto m = clusteredCube(3);
  const uint32_t stray = uint32_t(m.numPoints());
  m.points.push_back({0.5, 0.5, 0.5});
  for (auto& f : m.fields)
    for (auto& step : f.steps) step.push_back(100.0f);
  const auto without = extractClustersWithPointMap(m, {0});
  EXPECT_EQ(std::count(without.originalPoint.begin(), without.originalPoint.end(), stray), 0);
  const auto with = extractClustersWithPointMap(m, {0}, true);
  ASSERT_EQ(with.originalPoint.size(), without.originalPoint.size() + 1);
  EXPECT_EQ(with.originalPoint.back(), stray);  // the last point in the mesh's order
  EXPECT_EQ(with.mesh.points.back(), glm::dvec3(0.5, 0.5, 0.5));
  EXPECT_EQ(with.mesh.fields[0].steps[0].back(), 100.0f);
  EXPECT_EQ(with.mesh.numCells(), without.mesh.numCells());
}

TEST(ExtractClusters, KeepsPointsFieldsAndClustersOfTheSelection) {
  const auto m = clusteredCube(5);
  for (int c = 0; c < 5; ++c) {
    auto x = extractClustersWithPointMap(m, {c});
    const auto& sub = x.mesh;
    ASSERT_EQ(x.originalPoint.size(), sub.numPoints());
    EXPECT_TRUE(std::is_sorted(x.originalPoint.begin(), x.originalPoint.end()));
    EXPECT_EQ(std::adjacent_find(x.originalPoint.begin(), x.originalPoint.end()),
              x.originalPoint.end());
    std::vector<char> used(sub.numPoints(), 0);
    for (const auto& ids : sub.cells)
      for (uint32_t v : ids) used[v] = 1;
    EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0) << "unused points were kept";
    for (const auto& cl : sub.clusters)
      for (int32_t id : cl) EXPECT_EQ(id, c);
    EXPECT_EQ(sub.numCells(), clusterSizes(m)[c]);
    EXPECT_EQ(sub.timeValues, m.timeValues);
    ASSERT_EQ(sub.fields.size(), m.fields.size());
    for (size_t f = 0; f < m.fields.size(); ++f) {
      EXPECT_EQ(sub.fields[f].name, m.fields[f].name);
      ASSERT_EQ(sub.fields[f].numSteps(), m.fields[f].numSteps());
      for (size_t s = 0; s < m.fields[f].numSteps(); ++s)
        for (size_t i = 0; i < sub.numPoints(); ++i)
          ASSERT_EQ(sub.fields[f].steps[s][i], m.fields[f].steps[s][x.originalPoint[i]]);
    }
    for (size_t i = 0; i < sub.numPoints(); ++i)
      ASSERT_EQ(sub.points[i], m.points[x.originalPoint[i]]);
  }
}

TEST(ExtractClusters, AllClustersReassembleTheOriginal) {
  const auto m = clusteredCube(4);
  std::vector<uint32_t> identity(m.numPoints());
  for (uint32_t i = 0; i < identity.size(); ++i) identity[i] = i;
  std::vector<std::vector<uint32_t>> pieces;
  for (int c = 0; c < 4; ++c) {
    auto x = extractClustersWithPointMap(m, {c});
    auto tuples = elementTuples(x.mesh, x.originalPoint);
    pieces.insert(pieces.end(), tuples.begin(), tuples.end());
  }
  std::sort(pieces.begin(), pieces.end());
  EXPECT_EQ(pieces, elementTuples(m, identity));
  // All clusters at once is the input itself, points and order included.
  auto whole = extractClusters(m, {3, 1, 0, 2});
  EXPECT_EQ(whole.points, m.points);
  EXPECT_EQ(whole.cells, m.cells);
  EXPECT_EQ(whole.clusters, m.clusters);
}

TEST(ExtractClusters, FacesBetweenExtractedClustersStayShared) {
  const auto m = clusteredCube(5);
  auto faces = [&](std::vector<int> c) { return test::matchFaces(extractClusters(m, c)); };
  const auto zero = faces({0});
  int best = -1;
  uint64_t bestShared = 0;
  for (int c = 1; c < 5; ++c) {
    const auto other = faces({c}), both = faces({0, c});
    EXPECT_EQ(both.overShared + both.sameWinding, 0u);
    // Faces that were boundary of one cluster and are interior of the pair: the shared ones.
    const uint64_t shared = (zero.boundary + other.boundary - both.boundary) / 2;
    EXPECT_EQ(both.interior, zero.interior + other.interior + shared) << "cluster " << c;
    if (shared > bestShared) {
      best = c;
      bestShared = shared;
    }
  }
  EXPECT_GE(best, 1) << "cluster 0 touches no other cluster";
}

TEST(ExtractClusters, UnknownOrNoClustersGiveAnEmptyMeshWithFields) {
  const auto m = clusteredCube(3);
  for (const std::vector<int>& which : {std::vector<int>{}, std::vector<int>{7, -1}}) {
    auto sub = extractClusters(m, which);
    EXPECT_EQ(sub.numCells(), 0u);
    EXPECT_EQ(sub.numPoints(), 0u);
    ASSERT_EQ(sub.fields.size(), m.fields.size());
    EXPECT_EQ(sub.fields[0].numSteps(), 2u);
  }
}

}  // namespace
}  // namespace sm::partition
