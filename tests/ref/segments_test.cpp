// segments(): maximal runs of crossings of a predicate's elements, on hand-made crossing lists
// and on two-cluster cubes where the answer is known from the geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "ref/reference_renderer.h"
#include "test_meshes.h"

namespace sm::ref {
namespace {

using mesh::CellType;
using test::Split;

Crossing crossing(double a, double b, uint32_t index) {
  return {a, b, CellType::Tet, index};
}

ElementPredicate evenIndex() {
  return [](CellType, uint32_t index) { return index % 2 == 0; };
}

TEST(Segments, RunsBreakAtGapsAndForeignElements) {
  std::vector<Crossing> cs = {crossing(1.0, 2.0, 0), crossing(2.0, 3.0, 2),   // touching
                              crossing(3.5, 4.0, 4),                          // after a gap
                              crossing(4.0, 5.0, 1),                          // foreign
                              crossing(5.0, 6.0, 6), crossing(5.9, 7.0, 8)};  // overlapping
  auto segs = segments(cs, evenIndex());
  ASSERT_EQ(segs.size(), 3u);
  EXPECT_EQ(segs[0].tIn, 1.0);
  EXPECT_EQ(segs[0].tOut, 3.0);
  EXPECT_EQ(segs[0].first, 0u);
  EXPECT_EQ(segs[0].count, 2u);
  EXPECT_EQ(segs[1].tIn, 3.5);
  EXPECT_EQ(segs[1].tOut, 4.0);
  EXPECT_EQ(segs[1].first, 2u);
  EXPECT_EQ(segs[2].tIn, 5.0);
  EXPECT_EQ(segs[2].tOut, 7.0);
  EXPECT_EQ(segs[2].first, 4u);
  EXPECT_EQ(segs[2].count, 2u);
  // Without a predicate every crossing counts: the foreign one now joins its neighbours.
  auto all = segments(cs, {});
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[1].tIn, 3.5);
  EXPECT_EQ(all[1].count, 4u);
  EXPECT_TRUE(segments({}, evenIndex()).empty());
}

TEST(Segments, TouchingIsRelativeToDistance) {
  const double t = 1000.0;
  std::vector<Crossing> near = {crossing(t - 1, t, 0), crossing(t * (1 + 5e-10), t + 1, 2)};
  EXPECT_EQ(segments(near, {}).size(), 1u);
  std::vector<Crossing> far = {crossing(t - 1, t, 0), crossing(t * (1 + 5e-9), t + 1, 2)};
  EXPECT_EQ(segments(far, {}).size(), 2u);
  EXPECT_EQ(segments(far, {}, 1e-8).size(), 1u);
}

// Cube of 4^3 cells, clustered by x: `period` 2 gives two halves, 1 alternates every cell.
mesh::UnstructuredMesh slabClusters(Split split, int period) {
  return test::cubeMesh(split, 4, 1.0, glm::dvec3(0.0),
                        [period](int i, int, int) { return (i / period) % 2; });
}

TEST(Segments, TwoClusterCubesGiveKnownSegments) {
  for (Split split : {Split::Hex, Split::Tets6, Split::Pyramids}) {
    for (int period : {1, 2}) {
      auto m = slabClusters(split, period);
      ReferenceRenderer r(m);
      // Along +x through the interior, on grid lines (vertices and edges) and off them.
      for (glm::dvec2 yz : {glm::dvec2(0.3, 0.6), glm::dvec2(0.5, 0.5), glm::dvec2(0.25, 0.75)}) {
        auto cs = r.traceRay({-1.0, yz.x, yz.y}, {1, 0, 0});
        for (int32_t cluster : {0, 1}) {
          auto segs = segments(cs, clusterPredicate(m, {cluster}));
          const int expected = 2 / period;
          ASSERT_EQ(int(segs.size()), expected) << test::splitName(split);
          for (int k = 0; k < expected; ++k) {
            double start = 1.0 + 0.25 * period * (2 * k + cluster);
            EXPECT_NEAR(segs[k].tIn, start, 1e-12) << test::splitName(split);
            EXPECT_NEAR(segs[k].tOut, start + 0.25 * period, 1e-12) << test::splitName(split);
          }
        }
        EXPECT_EQ(segments(cs, clusterPredicate(m, {0, 1})).size(), 1u);
      }
    }
  }
}

TEST(Segments, ClustersPartitionRandomRays) {
  auto m = test::cubeMesh(Split::Tets5, 3, 1.0, glm::dvec3(0.0),
                          [](int i, int j, int k) { return (i + j + k) % 2; });
  ReferenceRenderer r(m);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0.05, 0.95), d(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    glm::dvec3 target(u(rng), u(rng), u(rng));
    glm::dvec3 origin = target + 2.0 * glm::normalize(glm::dvec3(d(rng), d(rng), d(rng)));
    auto cs = r.traceRay(origin, target - origin);
    auto s0 = segments(cs, clusterPredicate(m, {0}));
    auto s1 = segments(cs, clusterPredicate(m, {1}));
    // The two clusters' segments alternate along the ray and tile the cube's interval.
    std::vector<Segment> all = s0;
    all.insert(all.end(), s1.begin(), s1.end());
    std::sort(all.begin(), all.end(), [](auto& a, auto& b) { return a.tIn < b.tIn; });
    ASSERT_FALSE(all.empty());
    auto box = test::slab(glm::dvec3(0), glm::dvec3(1), origin, target - origin);
    EXPECT_NEAR(all.front().tIn, box.tIn, 1e-12);
    EXPECT_NEAR(all.back().tOut, box.tOut, 1e-12);
    for (size_t k = 1; k < all.size(); ++k) {
      EXPECT_NEAR(all[k].tIn, all[k - 1].tOut, 1e-12);
      // Touching runs of one cluster were merged, so neighbours belong to different clusters.
      EXPECT_NE(m.clusters[mesh::typeIndex(CellType::Tet)][cs[all[k].first].index],
                m.clusters[mesh::typeIndex(CellType::Tet)][cs[all[k - 1].first].index]);
    }
  }
}

}  // namespace
}  // namespace sm::ref
