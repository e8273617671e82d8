#include <gtest/gtest.h>

#include <cmath>

#include "io/mesh_io.h"
#include "io_test_util.h"
#include "mesh/element_geometry.h"
#include "support/test_support.h"

namespace sm::io {
namespace {

using mesh::CellType;
using test::cellIds;
using test::fileErrorOf;
using test::fixturePath;

class LegacyVersion : public ::testing::TestWithParam<const char*> {};

TEST_P(LegacyVersion, ReadsTheFixtureMesh) {
  // 4.2: CELLS n size with counts; 5.1: OFFSETS/CONNECTIVITY; SCALARS, VECTORS, FIELD, METADATA.
  mesh::UnstructuredMesh m = readMesh(fixturePath(GetParam()));
  test::expectFixtureMesh(m);
  test::expectAllPositive(m);
}

INSTANTIATE_TEST_SUITE_P(AllVersions, LegacyVersion,
                         ::testing::Values("mesh_v42_ascii.vtk", "mesh_v42_binary.vtk",
                                           "mesh_v51_ascii.vtk", "mesh_v51_binary.vtk"),
                         [](const auto& info) {
                           std::string n = info.param;
                           return n.substr(5, n.size() - 9);
                         });

// Cell data named as a field is averaged onto the points. The fixture's quality is i / 7 for cell
// i; point 11 is used by cell 3 alone, point 12 by cell 4 alone, point 0 by cells 0, 3, 4 and 6.
TEST(LegacyReader, CellDataNamedAsAFieldIsAveragedOntoThePoints) {
  const std::string path = fixturePath("mesh_v42_ascii.vtk");
  EXPECT_EQ(readMesh(path).cellArrays, std::vector<std::string>{"quality"});
  EXPECT_EQ(readMesh(path).findField("quality"), nullptr);
  ReadOptions o;
  o.fields = {"quality", "pressure"};
  const mesh::UnstructuredMesh m = readMesh(path, o);
  const mesh::Field* q = m.findField("quality");
  ASSERT_NE(q, nullptr);
  ASSERT_NE(m.findField("pressure"), nullptr);
  EXPECT_NEAR(q->steps[0][11], 3.0 / 7.0, 1e-6);
  EXPECT_NEAR(q->steps[0][12], 4.0 / 7.0, 1e-6);
  EXPECT_NEAR(q->steps[0][0], (0 + 3 + 4 + 6) / 7.0 / 4.0, 1e-6);
}

TEST(LegacyReader, SharedPostFile) {
  // Version 3.0, binary big-endian, float points, dataset FIELD data, POINT_DATA FIELD Pressure.
  mesh::UnstructuredMesh m = readMesh(sm::test::sharedDataPath("post.vtk"));
  ASSERT_EQ(m.numPoints(), 2288u);
  ASSERT_EQ(m.numCells(CellType::Tet), 8750u);
  EXPECT_EQ(m.numCells(), 8750u);
  EXPECT_EQ(m.points[1000], glm::dvec3(double(-2.839925527572632f), double(0.35876601934432983f),
                                       double(0.06506794691085815f)));
  ASSERT_EQ(m.fields.size(), 1u);
  EXPECT_EQ(m.fields[0].name, "Pressure");
  EXPECT_EQ(m.fields[0].steps[0][1000], 0.9941366910934448f);
  // VTK lists cell 5000 as 1156 1145 1431 1144; if that is inverted, 1 and 2 swap.
  std::vector<uint32_t> vtk = {1156, 1145, 1431, 1144};
  if (mesh::signedVolume(CellType::Tet, vtk, m.points) < 0) std::swap(vtk[1], vtk[2]);
  EXPECT_EQ(cellIds(m, CellType::Tet, 5000), vtk);
  test::expectAllPositive(m);
  EXPECT_TRUE(m.timeValues.empty());
}

TEST(LegacyReader, SharedNotchFile) {
  // Version 5.1 binary, vtktypeint64 OFFSETS/CONNECTIVITY, double points, names with %20.
  mesh::UnstructuredMesh m = readMesh(sm::test::sharedDataPath("notch_stress_fixed.vtk"));
  ASSERT_EQ(m.numPoints(), 3537u);
  EXPECT_EQ(m.numCells(CellType::Hex), 2188u);
  EXPECT_EQ(m.numCells(CellType::Wedge), 4u);
  EXPECT_EQ(m.points[2000], glm::dvec3(0.19506252067921812, 0.04820727448083813, 0.01));
  ASSERT_EQ(m.fields.size(), 3u);
  const mesh::Field* s0 = m.findField("Nodal Stress-0");
  const mesh::Field* s = m.findField("Nodal Stress");
  const mesh::Field* normed = m.findField("Nodal Stress-normed");
  ASSERT_TRUE(s0 && s && normed);
  EXPECT_EQ(s0->steps[0][2000], 3901345.4375f);
  EXPECT_FLOAT_EQ(normed->steps[0][2000], 4183967.7756290715f);
  const double t[6] = {3901345.4375,  1510015.125,      46.969072341918945,
                       70295.0078125, 1651.84033203125, -572.8574981689453};
  double sum = 0;
  for (double v : t) sum += v * v;
  EXPECT_FLOAT_EQ(s->steps[0][2000], float(std::sqrt(sum)));
  test::expectAllPositive(m);
  // VTK lists the first wedge (file cell 1172) as 3307 3340 3040 349 333 807.
  std::vector<uint32_t> wedge = {3307, 3340, 3040, 349, 333, 807};
  if (mesh::signedVolume(CellType::Wedge, wedge, m.points) < 0) {
    std::swap(wedge[1], wedge[2]);
    std::swap(wedge[4], wedge[5]);
  }
  EXPECT_EQ(cellIds(m, CellType::Wedge, 0), wedge);
  EXPECT_EQ(cellIds(m, CellType::Hex, 0).size(), 8u);
  ReadOptions o;
  o.fields = {"Nodal Stress[3]"};
  m = readMesh(sm::test::sharedDataPath("notch_stress_fixed.vtk"), o);
  ASSERT_EQ(m.fields.size(), 1u);
  EXPECT_EQ(m.fields[0].steps[0][2000], 70295.0078125f);
}

TEST(LegacyReader, EveryAttributeKindInAsciiFile) {
  const std::string dir = sm::test::outputDir("LegacyReader.EveryAttributeKind");
  const std::string path = dir + "/kinds.vtk";
  test::writeText(path, R"(# vtk DataFile Version 3.0
every attribute kind
ASCII
DATASET UNSTRUCTURED_GRID
FIELD FieldData 2
TimeValue 1 1 double
2.5
names 1 2 string
first%20name
second
POINTS 5 float
0 0 0  1 0 0  1 1 0  0 1 0  0.5 0.5 1
CELLS 2 11
5 0 1 2 3 4
4 0 1 2 4
CELL_TYPES 2
14
10
CELL_DATA 2
SCALARS partition int 1
LOOKUP_TABLE default
3 5
POINT_DATA 5
SCALARS T%20emp double 1
LOOKUP_TABLE default
1 2 3 4 5
METADATA
INFORMATION 0

NORMALS n float
0 0 1 0 0 1 0 0 1 0 0 1 0 0 1
TENSORS s float
1 0 0 0 0 0 0 0 0  2 0 0 0 0 0 0 0 0  3 0 0 0 0 0 0 0 0  4 0 0 0 0 0 0 0 0  5 0 0 0 0 0 0 0 0
TEXTURE_COORDINATES uv 2 float
0 0 1 0 1 1 0 1 0.5 0.5
GLOBAL_IDS ids vtkIdType
0 1 2 3 4
COLOR_SCALARS rgb 3
1 0 0 0 1 0 0 0 1 1 1 0 0 1 1
LOOKUP_TABLE mytable 2
0 0 0 1 1 1 1 1
FIELD extra 1
flags 1 5 bit
0 1 0 1 1
)");
  mesh::UnstructuredMesh m = readMesh(path);
  EXPECT_EQ(m.numCells(CellType::Pyramid), 1u);
  EXPECT_EQ(m.numCells(CellType::Tet), 1u);
  EXPECT_EQ(m.clusters[mesh::typeIndex(CellType::Pyramid)], (std::vector<int32_t>{3}));
  EXPECT_EQ(m.clusters[mesh::typeIndex(CellType::Tet)], (std::vector<int32_t>{5}));
  EXPECT_EQ(m.timeValues, (std::vector<double>{2.5}));
  std::vector<std::string> names;
  for (const auto& f : m.fields) names.push_back(f.name);
  EXPECT_EQ(names, (std::vector<std::string>{"T emp", "n", "s", "uv", "rgb", "flags"}));
  EXPECT_EQ(m.findField("T emp")->steps[0][3], 4.0f);
  EXPECT_EQ(m.findField("s")->steps[0][4], 5.0f);
  EXPECT_FLOAT_EQ(m.findField("uv")->steps[0][2], float(std::sqrt(2.0)));
  EXPECT_EQ(m.findField("flags")->steps[0], (std::vector<float>{0, 1, 0, 1, 1}));
  ReadOptions o;
  o.fields = {"ids"};
  EXPECT_EQ(readMesh(path, o).fields[0].steps[0][4], 4.0f);
}

// vtkGhostType: DUPLICATECELL (1, another piece's) and HIDDENCELL (32, blanked) cells are left
// out; other flags (2: high connectivity) and none keep the cell. Four tetrahedra on a shared
// base, told apart by their apex point.
TEST(LegacyReader, GhostCellsOwnedElsewhereOrHiddenAreSkipped) {
  const std::string path = sm::test::outputDir("LegacyReader.GhostCells") + "/ghosts.vtk";
  test::writeText(path, R"(# vtk DataFile Version 3.0
ghost cells
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 7 float
0 0 0  1 0 0  0 1 0  0 0 1  0 0 2  0 0 3  0 0 4
CELLS 4 20
4 0 1 2 3
4 0 1 2 4
4 0 1 2 5
4 0 1 2 6
CELL_TYPES 4
10 10 10 10
CELL_DATA 4
SCALARS vtkGhostType unsigned_char 1
LOOKUP_TABLE default
0 1 32 2
)");
  test::expectGhostCellsSkipped(path, {1.0, 4.0});
}

TEST(LegacyReader, RejectsOtherDataSets) {
  const std::string path = sm::test::outputDir("LegacyReader.RejectsOtherDataSets") + "/poly.vtk";
  test::writeText(path, "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 0 float\n");
  std::string msg = fileErrorOf([&] { readMesh(path); });
  EXPECT_NE(msg.find("poly.vtk"), std::string::npos) << msg;
  EXPECT_NE(msg.find("polydata"), std::string::npos) << msg;
}

}  // namespace
}  // namespace sm::io
