#include <gtest/gtest.h>

#include <map>

#include "partition_free_extract.h"
#include "prep/prepare.h"
#include "prep/vertex_order.h"
#include "support/test_meshes.h"

namespace sm::prep {
namespace {

// Two ranks holding different halves of a mesh must order their shared vertices identically (the
// quad split rule and canonical crossing distances depend on it), and rebase them bit-identically.
TEST(VertexOrder, RanksAgreeOnSharedVertices) {
  auto whole = test::kuhnTetGrid(4, 1.0, glm::dvec3(5e5, 0, 0), /*clusters=*/2);
  auto frame = makeGlobalFrame(whole.bounds());
  auto r0 = test::clusterSubset(whole, 0), r1 = test::clusterSubset(whole, 1);
  auto p0 = prepareRank(r0.mesh, frame, PrepOptions{}).rank;
  auto p1 = prepareRank(r1.mesh, frame, PrepOptions{}).rank;
  // Map whole-mesh vertex -> rank-local index in each rank.
  std::map<uint32_t, uint32_t> l0, l1;
  for (uint32_t i = 0; i < p0.numVertices(); ++i) l0[r0.original[p0.vertexSource[i]]] = i;
  for (uint32_t i = 0; i < p1.numVertices(); ++i) l1[r1.original[p1.vertexSource[i]]] = i;
  std::vector<uint32_t> shared;
  for (auto& [g, i] : l0)
    if (l1.count(g)) shared.push_back(g);
  ASSERT_GT(shared.size(), 10u);
  for (size_t a = 0; a < shared.size(); ++a) {
    uint32_t ga = shared[a];
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(p0.positions[3 * l0[ga] + c], p1.positions[3 * l1[ga] + c]);
    for (size_t b = a + 1; b < shared.size(); ++b) {
      uint32_t gb = shared[b];
      EXPECT_EQ(l0[ga] < l0[gb], l1[ga] < l1[gb]) << "vertices " << ga << ", " << gb;
    }
  }
}

TEST(VertexOrder, MortonCodeInterleavesAxes) {
  mesh::Bounds b;
  b.extend(glm::dvec3(0.0));
  b.extend(glm::dvec3(1.0));
  EXPECT_EQ(mortonCode(glm::dvec3(0.0), b), 0u);
  EXPECT_EQ(mortonCode(glm::dvec3(1, 0, 0), b) & 7u, 1u);
  EXPECT_EQ(mortonCode(glm::dvec3(0, 1, 0), b) & 7u, 2u);
  EXPECT_EQ(mortonCode(glm::dvec3(0, 0, 1), b) & 7u, 4u);
}

}  // namespace
}  // namespace sm::prep
