#include <gtest/gtest.h>

#include "common/error.h"
#include "mesh/mesh_builder.h"
#include "prep/connectivity.h"
#include "prep/prepare.h"
#include "support/test_meshes.h"

namespace sm::prep {
namespace {

// Neighbour relations must be symmetric: if A's face slot points to B, one of B's slots points to
// A.
void expectSymmetric(const PreparedRank& r) {
  for (uint32_t t = 0; t < 4; ++t) {
    const uint32_t nf = gpu::SM_NUM_FACES[t];
    for (uint64_t e = 0; e < r.elementCount[t]; ++e) {
      for (uint32_t s = 0; s < nf; ++s) {
        uint32_t ref = r.neighbors[t][e * nf + s];
        if (ref == gpu::SM_NO_NEIGHBOR) continue;
        uint32_t nt = gpu::smRefType(ref), ne = gpu::smRefIndex(ref);
        ASSERT_LT(ne, r.elementCount[nt]);
        int back = 0;
        for (uint32_t k = 0; k < gpu::SM_NUM_FACES[nt]; ++k)
          back += r.neighbors[nt][uint64_t(ne) * gpu::SM_NUM_FACES[nt] + k] ==
                  gpu::smElemRef(uint32_t(e), t);
        EXPECT_EQ(back, 1) << "type " << t << " element " << e << " slot " << s;
      }
    }
  }
}

TEST(Connectivity, HexGridCounts) {
  const int n = 4;
  auto m = test::hexGrid(n);
  auto res = prepareRank(m, makeGlobalFrame(m.bounds()), PrepOptions{});
  EXPECT_EQ(res.connectivity.interiorFaces, uint64_t(3 * n * n * (n - 1)));
  EXPECT_EQ(res.connectivity.boundaryFaces, uint64_t(6 * n * n));
  EXPECT_EQ(res.rank.numShellTriangles(), uint64_t(12 * n * n));
  expectSymmetric(res.rank);
}

TEST(Connectivity, TetGridCounts) {
  const int n = 3;
  auto m = test::kuhnTetGrid(n);
  auto res = prepareRank(m, makeGlobalFrame(m.bounds()), PrepOptions{});
  EXPECT_EQ(res.connectivity.boundaryFaces, uint64_t(12 * n * n));
  // 6 tets x 4 faces per cell, each interior face counted once.
  EXPECT_EQ(2 * res.connectivity.interiorFaces + res.connectivity.boundaryFaces,
            uint64_t(24 * n * n * n));
  expectSymmetric(res.rank);
}

// The message preparing `m` fails with ("" when it does not fail).
std::string preparationError(mesh::UnstructuredMesh& m) {
  try {
    prepareRank(m, makeGlobalFrame(m.bounds()), PrepOptions{});
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Connectivity, FaceSharedByThreeElementsIsAnError) {
  mesh::MeshBuilder b("fan.vtu");
  b.setPoints({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}, {1, 1, 1}});
  const int64_t t0[4] = {0, 1, 2, 3}, t1[4] = {0, 2, 1, 4}, t2[4] = {0, 1, 2, 5};
  b.addVtkCell(10, t0, 0);
  b.addVtkCell(10, t1, 1);
  b.addVtkCell(10, t2, 2);
  auto m = b.finish();
  const std::string msg = preparationError(m);
  EXPECT_NE(msg.find("fan.vtu"), std::string::npos) << msg;
  EXPECT_NE(msg.find("shared by 3 elements"), std::string::npos) << msg;
  EXPECT_NE(msg.find("tetrahedron #"), std::string::npos) << msg;
}

// A duplicated cell would pair each of its faces with its twin's: both vanish from the shell (or,
// beside a neighbour, a face looks shared by three). It is named as a duplicate, with a position.
TEST(Connectivity, DuplicatedCellsAreAnError) {
  for (bool withNeighbour : {false, true}) {
    mesh::MeshBuilder b("dup.vtu");
    b.setPoints({{0, 0, 0},
                 {1, 0, 0},
                 {0, 1, 0},
                 {0, 0, 1},
                 {0, 0, -1},
                 {5, 5, 5},
                 {6, 5, 5},
                 {5, 6, 5},
                 {5, 5, 6}});
    const int64_t t0[4] = {0, 1, 2, 3}, again[4] = {1, 0, 3, 2}, below[4] = {0, 2, 1, 4},
                  apart[4] = {5, 6, 7, 8};
    b.addVtkCell(10, t0, 0);
    b.addVtkCell(10, again, 1);  // the same vertices, listed otherwise (fixed to positive volume)
    b.addVtkCell(10, apart, 2);
    if (withNeighbour) b.addVtkCell(10, below, 3);
    auto m = b.finish();
    const std::string msg = preparationError(m);
    EXPECT_NE(msg.find("dup.vtu: two tetrahedra have the same vertices"), std::string::npos) << msg;
    EXPECT_NE(msg.find("at (0, 0, 0)"), std::string::npos) << msg;
  }
}

// Points whose distance from the centre float cannot hold (the extent itself overflows, so no
// power-of-two scale applies) are refused, naming the file.
TEST(Connectivity, PointsBeyondFloatRangeOfTheCentreAreRefused) {
  mesh::MeshBuilder b("huge.vtu");
  b.setPoints({{-1.7e308, 0, 0}, {1.7e308, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  const int64_t t[4] = {0, 1, 2, 3};
  b.addVtkCell(10, t, 0);
  auto m = b.finish();
  const std::string msg = preparationError(m);
  EXPECT_NE(msg.find("huge.vtu: point"), std::string::npos) << msg;
  EXPECT_NE(msg.find("too far from the mesh's centre for single precision"), std::string::npos)
      << msg;
}

TEST(Connectivity, EmptyMeshPreparesToNothing) {
  mesh::UnstructuredMesh m;
  auto res = prepareRank(m, makeGlobalFrame(m.bounds()), PrepOptions{});
  EXPECT_EQ(res.rank.numElements(), 0u);
  EXPECT_EQ(res.rank.numShellTriangles(), 0u);
}

}  // namespace
}  // namespace sm::prep
