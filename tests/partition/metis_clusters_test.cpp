#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "common/error.h"
#include "gen/generate.h"
#include "partition/partition.h"

namespace sm::partition {
namespace {

using mesh::CellType;

std::vector<int32_t> allClusters(const mesh::UnstructuredMesh& m) {
  std::vector<int32_t> all;
  for (const auto& c : m.clusters) all.insert(all.end(), c.begin(), c.end());
  return all;
}

void expectEveryElementInOneOfNClusters(const mesh::UnstructuredMesh& m, int n) {
  for (CellType t : mesh::kAllCellTypes)
    EXPECT_EQ(m.clusters[mesh::typeIndex(t)].size(), m.numCells(t));
  for (int32_t c : allClusters(m)) ASSERT_TRUE(c >= 0 && c < n) << c;
  auto sizes = clusterSizes(m);
  ASSERT_EQ(int(sizes.size()), n);
  for (uint64_t s : sizes) EXPECT_GT(s, 0u);
  EXPECT_EQ(std::accumulate(sizes.begin(), sizes.end(), uint64_t(0)), m.numCells());
}

TEST(MetisClusters, SplitsACubeIntoBalancedNonEmptyClusters) {
  auto m = gen::cube(gen::CubeSplit::Tets6, 8);  // 3072 tetrahedra
  assignMetisClusters(m, 7);
  expectEveryElementInOneOfNClusters(m, 7);
  auto sizes = clusterSizes(m);
  const double mean = double(m.numCells()) / 7;
  for (uint64_t s : sizes) EXPECT_LT(double(s), 1.1 * mean);
}

TEST(MetisClusters, IsDeterministicForAMeshAndSeed) {
  auto a = gen::cube(gen::CubeSplit::Pyramids, 5), b = gen::cube(gen::CubeSplit::Pyramids, 5);
  assignMetisClusters(a, 6, 42);
  assignMetisClusters(b, 6, 42);
  EXPECT_EQ(a.clusters, b.clusters);
  // Running again on the same mesh overwrites rather than depends on old ids.
  assignMetisClusters(a, 6, 42);
  EXPECT_EQ(a.clusters, b.clusters);
}

TEST(MetisClusters, HandlesOneClusterAndMoreClustersThanElements) {
  auto m = gen::zoo();
  assignMetisClusters(m, 1);
  expectEveryElementInOneOfNClusters(m, 1);
  assignMetisClusters(m, 100);  // six elements: one cluster each
  expectEveryElementInOneOfNClusters(m, int(m.numCells()));
  assignMetisClusters(m, 2);
  expectEveryElementInOneOfNClusters(m, 2);
  EXPECT_THROW(assignMetisClusters(m, 0), Error);
}

TEST(MetisClusters, FillsPartsMetisLeavesEmpty) {
  // Two disconnected cubes of 1 and 125 hexahedra: asking for many parts of such a graph can
  // leave METIS with empty ones; every cluster must still get an element.
  auto m = gen::cube(gen::CubeSplit::Hex, 5);
  mesh::UnstructuredMesh far = gen::cube(gen::CubeSplit::Hex, 1);
  for (auto& p : far.points) p += glm::dvec3(10.0);
  mesh::append(m, far);
  for (int n : {2, 3, 17, 60, 125}) {
    assignMetisClusters(m, n);
    expectEveryElementInOneOfNClusters(m, n);
  }
}

TEST(MetisClusters, PartitionsMixedElementMeshes) {
  gen::CfdMeshOptions o;
  o.targetElements = 12000;
  o.clusters = 1;
  o.threads = 1;
  auto m = gen::generateCfdMesh(o);
  assignMetisClusters(m, 8, 3);
  expectEveryElementInOneOfNClusters(m, 8);
  // Every element type takes part (METIS sees all of them in one dual graph).
  for (CellType t : mesh::kAllCellTypes) {
    const auto& c = m.clusters[mesh::typeIndex(t)];
    ASSERT_FALSE(c.empty());
    EXPECT_GT(*std::max_element(c.begin(), c.end()), 0) << mesh::cellTypeName(t);
  }
}

}  // namespace
}  // namespace sm::partition
