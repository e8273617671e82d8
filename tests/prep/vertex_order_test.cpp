#include <gtest/gtest.h>

#include <algorithm>
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

// Elements are reordered by their smallest vertex id, stably, each element's vertex list intact.
TEST(VertexOrder, ElementsFollowTheirSmallestVertex) {
  ElementArrays e;
  e[gpu::SM_TET] = {5, 9, 7, 8, 2, 6, 3, 4, 9, 5, 8, 6, 2, 1, 7, 3};
  e[gpu::SM_WED] = {4, 5, 6, 7, 8, 9};  // one element: unchanged
  orderElementsByVertex(e, 10);
  EXPECT_EQ(e[gpu::SM_TET],
            (std::vector<uint32_t>{2, 1, 7, 3, 2, 6, 3, 4, 5, 9, 7, 8, 9, 5, 8, 6}));
  EXPECT_EQ(e[gpu::SM_WED], (std::vector<uint32_t>{4, 5, 6, 7, 8, 9}));
}

// After preparation, elements of every type lie in the order of their smallest global vertex (what
// makes a walk's reads local), and the mesh is the same mesh: every face still has its neighbour.
TEST(VertexOrder, PreparedElementsAreInVertexOrder) {
  auto m = test::kuhnTetGrid(5);
  PrepOptions plain;
  plain.compact = false;
  auto r = prepareRank(m, makeGlobalFrame(m.bounds()), plain).rank;
  const std::vector<uint32_t>& tets = r.elements[gpu::SM_TET];
  ASSERT_EQ(tets.size(), 4u * 6 * 5 * 5 * 5);
  uint32_t last = 0;
  for (size_t i = 0; i < tets.size(); i += 4) {
    uint32_t k = std::min({tets[i], tets[i + 1], tets[i + 2], tets[i + 3]});
    EXPECT_LE(last, k) << "element " << i / 4;
    last = k;
  }
}

}  // namespace
}  // namespace sm::prep
