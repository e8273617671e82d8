#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"
#include "mesh/element_geometry.h"
#include "mesh/mesh_builder.h"

namespace sm::mesh {
namespace {

std::vector<glm::dvec3> wedgePoints() {
  // VTK's own Wedge.vtu: triangle (0,1,2) faces (3,4,5), which VTK's validator calls inverted.
  return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
}

TEST(MeshBuilder, FixesInvertedCellsAndKeepsVolumePositive) {
  MeshBuilder b("wedge.vtu");
  b.setPoints(wedgePoints());
  const int64_t ids[6] = {0, 1, 2, 3, 4, 5};
  b.addVtkCell(13, ids, 0);
  auto m = b.finish();
  ASSERT_EQ(m.numCells(CellType::Wedge), 1u);
  EXPECT_EQ(m.invertedFixed, 1u);
  EXPECT_GT(signedVolume(CellType::Wedge, m.cells[2], m.points), 0.0);
}

TEST(MeshBuilder, SkipsAndCountsNonVolumeCells) {
  MeshBuilder b("mixed.vtk");
  b.setPoints(wedgePoints());
  const int64_t tri[3] = {0, 1, 2}, line[2] = {0, 1};
  b.addVtkCell(5, tri, 0);
  b.addVtkCell(3, line, 1);
  b.addVtkCell(42, tri, 2);
  auto m = b.finish();
  EXPECT_EQ(m.numCells(), 0u);
  EXPECT_EQ(m.skipped.surface, 1u);
  EXPECT_EQ(m.skipped.lineOrVertex, 1u);
  EXPECT_EQ(m.skipped.polyhedra, 1u);
}

TEST(MeshBuilder, ReducesQuadraticTetToCorners) {
  MeshBuilder b("q.vtu");
  std::vector<glm::dvec3> p(10, glm::dvec3(0.5));
  p[0] = {0, 0, 0};
  p[1] = {1, 0, 0};
  p[2] = {0, 1, 0};
  p[3] = {0, 0, 1};
  b.setPoints(p);
  const int64_t ids[10] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  b.addVtkCell(24, ids, 0);
  auto m = b.finish();
  EXPECT_EQ(m.numCells(CellType::Tet), 1u);
  EXPECT_EQ(m.skipped.quadraticReduced, 1u);
}

// Lagrange and Bezier cells come in any order; order 1 has the corners only (nothing reduced).
// Curves (68, 75) are lines, triangles and quadrilaterals (69, 70, 76, 77) surfaces.
TEST(MeshBuilder, LagrangeAndBezierCellsOfEveryKind) {
  MeshBuilder b("lagrange.vtu");
  b.setPoints(wedgePoints());
  const int64_t tet[4] = {0, 1, 2, 3}, line[2] = {0, 1}, quad[4] = {0, 1, 4, 3};
  b.addVtkCell(71, tet, 0);
  b.addVtkCell(78, tet, 1);
  b.addVtkCell(75, line, 2);
  b.addVtkCell(68, line, 3);
  b.addVtkCell(77, quad, 4);
  b.addVtkCell(70, quad, 5);
  auto m = b.finish();
  EXPECT_EQ(m.numCells(CellType::Tet), 2u);
  EXPECT_EQ(m.skipped.quadraticReduced, 0u);
  EXPECT_EQ(m.skipped.lineOrVertex, 2u);
  EXPECT_EQ(m.skipped.surface, 2u);
}

// Ids far above the cell count (2^31 - 1 once overflowed the cluster count, and each id sized
// per-cluster arrays) are renumbered densely in order; small ids stay as the file gives them.
TEST(MeshBuilder, SparseClusterIdsAreRenumberedInOrder) {
  for (bool sparse : {false, true}) {
    MeshBuilder b("clusters.vtu");
    b.setPoints(wedgePoints());
    const int64_t tet[4] = {0, 1, 2, 3};
    for (int c = 0; c < 3; ++c) b.addVtkCell(10, tet, c);
    const std::vector<int64_t> ids =
        sparse ? std::vector<int64_t>{2147483647, 7, 100000000} : std::vector<int64_t>{9, 7, 30};
    b.setClusterIds(ids, "cluster");
    auto m = b.finish();
    const std::vector<int32_t> want =
        sparse ? std::vector<int32_t>{2, 0, 1} : std::vector<int32_t>{9, 7, 30};
    EXPECT_EQ(m.clusters[typeIndex(CellType::Tet)], want);
    EXPECT_EQ(m.numClusters(), sparse ? 3 : 31);
  }
}

TEST(MeshBuilder, ErrorsNameFileAndCell) {
  MeshBuilder b("bad.vtu");
  b.setPoints(wedgePoints());
  const int64_t outOfRange[4] = {0, 1, 2, 17};
  try {
    b.addVtkCell(10, outOfRange, 42);
    FAIL() << "expected an error";
  } catch (const FileError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("bad.vtu"), std::string::npos) << msg;
    EXPECT_NE(msg.find("cell 42"), std::string::npos) << msg;
    EXPECT_NE(msg.find("17"), std::string::npos) << msg;
  }
  const int64_t repeated[4] = {0, 1, 1, 3};
  EXPECT_THROW(b.addVtkCell(10, repeated, 7), FileError);
  const int64_t tooFew[3] = {0, 1, 2};
  EXPECT_THROW(b.addVtkCell(12, tooFew, 8), FileError);
}

// Damage shows in ids the renderer would not use: a skipped cell's, a quadratic cell's midside
// nodes, a linear cell listing more points than it has (a wrong offset). All are errors.
TEST(MeshBuilder, EveryIdOfEveryCellNamesAPoint) {
  MeshBuilder b("bad.vtk");
  std::vector<glm::dvec3> p(10, glm::dvec3(0.5));
  p[1] = {1, 0, 0};
  p[2] = {0, 1, 0};
  p[3] = {0, 0, 1};
  b.setPoints(p);
  auto message = [&](int type, std::vector<int64_t> ids) {
    try {
      b.addVtkCell(type, ids, 5);
    } catch (const FileError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(5, {0, 1, 77}),
            "bad.vtk: cell 5 (VTK type 5) refers to point 77 but the file has 10 points");
  EXPECT_EQ(message(3, {-1, 1}),
            "bad.vtk: cell 5 (VTK type 3) refers to point -1 but the file has 10 points");
  EXPECT_EQ(message(24, {0, 1, 2, 3, 4, 5, 6, 7, 8, 10}),
            "bad.vtk: cell 5 (VTK type 24) refers to point 10 but the file has 10 points");
  EXPECT_EQ(message(10, {0, 1, 2, 3, 4}), "bad.vtk: cell 5 (VTK type 10) has 5 points, expected 4");
  EXPECT_EQ(message(12, {0, 1, 2, 3, 4, 5, 6, 7, 8}),
            "bad.vtk: cell 5 (VTK type 12) has 9 points, expected 8");
  EXPECT_EQ(message(42, {3, 0, 99, 1}), "no error");  // a polyhedron's face stream is not ids
  EXPECT_EQ(message(10, {0, 1, 2, 3}), "no error");
  EXPECT_EQ(message(24, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9}), "no error");
}

TEST(MeshBuilder, RejectsNonFiniteCoordinates) {
  MeshBuilder b("nan.vtu");
  EXPECT_THROW(b.setPoints({{0, 0, 0}, {std::nan(""), 0, 0}}), FileError);
}

TEST(MeshBuilder, FieldSizeMismatchIsAnError) {
  MeshBuilder b("f.vtu");
  b.setPoints(wedgePoints());
  EXPECT_THROW(b.addFieldStep("p", 0, std::vector<float>(3, 1.0f)), FileError);
}

TEST(MeshBuilder, ClusterIdsFollowFileCells) {
  MeshBuilder b("c.vtu");
  b.setPoints({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}});
  const int64_t t0[4] = {0, 1, 2, 3}, tri[3] = {0, 1, 2}, t1[4] = {1, 2, 3, 4};
  b.addVtkCell(10, t0, 0);
  b.addVtkCell(5, tri, 1);
  b.addVtkCell(10, t1, 2);
  const int64_t ids[3] = {7, 8, 9};
  b.setClusterIds(ids, "cluster");
  auto m = b.finish();
  ASSERT_EQ(m.clusters[0].size(), 2u);
  EXPECT_EQ(m.clusters[0][0], 7);
  EXPECT_EQ(m.clusters[0][1], 9);
  EXPECT_EQ(m.numClusters(), 10);
}

std::string pointCountRefusal(uint64_t points) {
  try {
    checkPointCount("big.vtu", points, "declares", "use more ranks");
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

// Vertex ids are 32-bit: 2^32 - 1 points fit (ids 0 .. 2^32 - 2), one more is refused by count
// alone, naming the file, the limit and what would fit; no points are made.
TEST(MeshBuilder, PointCountsPast32BitIdsAreRefusedAtTheBoundary) {
  EXPECT_EQ(kMaxMeshPoints, 0xFFFFFFFFull);
  EXPECT_EQ(pointCountRefusal(kMaxMeshPoints), "");
  EXPECT_EQ(pointCountRefusal(kMaxMeshPoints + 1),
            "big.vtu: declares 4294967296 points: vertex ids are 32-bit, so one mesh holds at most "
            "4294967295 (use more ranks)");
  EXPECT_NE(pointCountRefusal(UINT64_MAX), "");
}

// Cell origins are 32-bit too: kept for up to 2^32 - 1 file cells, refused past that before any
// cell is read. Without origins, file cell numbers past 2^32 are only counted (64-bit).
TEST(MeshBuilder, CellOriginsAreKeptUpTo32BitsAndCellNumbersRunPast) {
  MeshBuilder ok("c.vtu");
  EXPECT_NO_THROW(ok.keepCellOrigins(0xFFFFFFFFull));
  MeshBuilder big("c.vtu");
  try {
    big.keepCellOrigins(uint64_t(1) << 32);
    ADD_FAILURE() << "2^32 cells' origins kept";
  } catch (const FileError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("c.vtu: has 4294967296 cells", 0), 0u) << msg;
    EXPECT_NE(msg.find("at most 4294967295"), std::string::npos) << msg;
    EXPECT_NE(msg.find("use more ranks"), std::string::npos) << msg;
  }
  MeshBuilder far("far.vtu");
  far.setFileCells((uint64_t(1) << 33) + 1);
  far.setPoints({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  const int64_t tet[4] = {0, 1, 2, 3};
  far.addVtkCell(10, tet, uint64_t(1) << 33);
  const UnstructuredMesh m = far.finish();
  EXPECT_EQ(m.numCells(), 1u);
  EXPECT_TRUE(m.cellOrigin.empty());  // none asked for, none that could be kept
}

}  // namespace
}  // namespace sm::mesh
