#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <utility>

#include "io/mesh_io.h"
#include "io_test_util.h"
#include "support/test_support.h"

namespace sm::io {
namespace {

using mesh::CellType;
using test::cellIds;
using test::fileErrorOf;
using test::fixturePath;

// Every encoding VTK's writer produces, and a hand-made file, hold the same mesh.
class VtuEncoding : public ::testing::TestWithParam<const char*> {};

TEST_P(VtuEncoding, ReadsTheFixtureMesh) {
  mesh::UnstructuredMesh m = readMesh(fixturePath(GetParam()));
  test::expectFixtureMesh(m);
  test::expectAllPositive(m);
}

INSTANTIATE_TEST_SUITE_P(
    AllEncodings, VtuEncoding,
    ::testing::Values("mesh_ascii.vtu", "mesh_binary_none_h32.vtu", "mesh_binary_none_h64.vtu",
                      "mesh_binary_zlib_h32.vtu", "mesh_binary_zlib_h64.vtu",
                      "mesh_appended_raw_none_h32.vtu", "mesh_appended_raw_none_h64.vtu",
                      "mesh_appended_raw_zlib_h32.vtu", "mesh_appended_raw_zlib_h64.vtu",
                      "mesh_appended_b64_none_h32.vtu", "mesh_appended_b64_none_h64.vtu",
                      "mesh_appended_b64_zlib_h32.vtu", "mesh_appended_b64_zlib_h64.vtu",
                      "mesh_binary_zlib_id32.vtu", "mesh_appended_raw_none_id32.vtu",
                      "mesh_appended_raw_none_bigendian.vtu", "mesh_binary_zlib_bigendian.vtu",
                      "mesh_appended_raw_zlib_float32.vtu", "mesh_lz4.vtu", "mesh_lzma.vtu"),
    [](const auto& info) {
      std::string n = info.param;
      return n.substr(5, n.size() - 9);  // "mesh_" ... ".vtu"
    });

TEST(VtuReader, EveryIntegerTypeAndANamedClusterArray) {
  // UInt16 connectivity, UInt32 offsets, Int8 types; Int16, UInt64 (2 components), Int8 fields;
  // cluster ids in a UInt8 cell array "part".
  ReadOptions o;
  o.clusterArray = "part";
  mesh::UnstructuredMesh m = readMesh(fixturePath("mesh_int_types.vtu"), o);
  test::expectFixtureGeometry(m);
  const mesh::Field* p = m.findField("pressure");
  const mesh::Field* big = m.findField("big");
  const mesh::Field* small = m.findField("small");
  ASSERT_TRUE(p && big && small);
  for (int i = 0; i < 13; ++i) {
    EXPECT_EQ(p->steps[0][i], 10.0f * i);
    EXPECT_FLOAT_EQ(big->steps[0][i], float(std::sqrt(2.0) * i));
    EXPECT_EQ(small->steps[0][i], -1.0f * i);
  }
}

TEST(VtuReader, WithoutAClusterArrayEveryCellIsClusterZero) {
  // mesh_int_types.vtu names its cluster array "part", which is not a default name.
  mesh::UnstructuredMesh m = readMesh(fixturePath("mesh_int_types.vtu"));
  EXPECT_EQ(m.numClusters(), 1);
}

TEST(VtuReader, SelectsFieldsComponentsAndSteps) {
  ReadOptions o;
  o.fields = {"velocity[1]", "temp", "velocity"};
  mesh::UnstructuredMesh m = readMesh(fixturePath("mesh_appended_raw_zlib_h64.vtu"), o);
  ASSERT_EQ(m.fields.size(), 3u);
  EXPECT_EQ(m.fields[0].name, "velocity[1]");
  EXPECT_EQ(m.fields[1].name, "temp");
  EXPECT_EQ(m.fields[1].numSteps(), 3u);
  EXPECT_EQ(m.fields[2].name, "velocity");
  EXPECT_EQ(m.fields[0].steps[0][5], 10.0f);
  EXPECT_FLOAT_EQ(m.fields[2].steps[0][5], float(5 * std::sqrt(6.0)));
  EXPECT_EQ(m.fields[1].steps[2][5], 205.0f);
  // A component is written in decimal without leading zeros, as a step is: "velocity[01]" would
  // be an array of that name, which the file lacks.
  o.fields = {"velocity[01]"};
  std::string msg =
      fileErrorOf([&] { readMesh(fixturePath("mesh_appended_raw_zlib_h64.vtu"), o); });
  EXPECT_NE(msg.find("'velocity[01]'"), std::string::npos) << msg;
  for (const char* signed_ : {"velocity[-0]", "velocity[+1]"}) {
    o.fields = {signed_};
    msg = fileErrorOf([&] { readMesh(fixturePath("mesh_appended_raw_zlib_h64.vtu"), o); });
    EXPECT_NE(msg.find(std::string("'") + signed_ + "'"), std::string::npos) << msg;
  }
}

TEST(VtuReader, NoFieldsWhenNotAsked) {
  ReadOptions o;
  o.loadFields = false;
  mesh::UnstructuredMesh m = readMesh(fixturePath("mesh_binary_zlib_h32.vtu"), o);
  EXPECT_TRUE(m.fields.empty());
  test::expectFixtureGeometry(m);
}

TEST(VtuReader, UnknownFieldListsTheArraysTheFileHas) {
  ReadOptions o;
  o.fields = {"density"};
  std::string msg = fileErrorOf([&] { readMesh(fixturePath("mesh_ascii.vtu"), o); });
  EXPECT_NE(msg.find("mesh_ascii.vtu"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'density'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("pressure"), std::string::npos) << msg;
  EXPECT_NE(msg.find("velocity (3 components)"), std::string::npos) << msg;
  o.fields = {"velocity[3]"};
  msg = fileErrorOf([&] { readMesh(fixturePath("mesh_ascii.vtu"), o); });
  EXPECT_NE(msg.find("3 components"), std::string::npos) << msg;
}

// Solvers often write cell data only. Named by a field request it is averaged onto the points
// (each point the mean of the cells around it, VTK's Cell Data to Point Data), for a .vtu as for
// the pieces of a .pvtu joined first; not named, it is listed, and messages say what it is.
std::string twoTets(const std::vector<std::string>& apexes, const std::string& cellData) {
  std::string pts = "0 0 0  1 0 0  0 1 0";
  for (const auto& a : apexes) pts += "  " + a;
  const size_t n = apexes.size();
  std::string conn, offsets, types;
  for (size_t i = 0; i < n; ++i) {
    conn += "0 1 2 " + std::to_string(3 + i) + " ";
    offsets += std::to_string(4 * (i + 1)) + " ";
    types += "10 ";
  }
  return R"(<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian">
<UnstructuredGrid><Piece NumberOfPoints=")" +
         std::to_string(3 + n + 1) + R"(" NumberOfCells=")" + std::to_string(n) + R"(">
<Points><DataArray type="Float32" NumberOfComponents="3" format="ascii">)" +
         pts + R"(  5 5 5</DataArray></Points>
<Cells><DataArray type="Int32" Name="connectivity" format="ascii">)" +
         conn + R"(</DataArray>
<DataArray type="Int32" Name="offsets" format="ascii">)" +
         offsets + R"(</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">)" +
         types + R"(</DataArray></Cells>
<CellData>)" +
         cellData +
         R"(</CellData>
</Piece></UnstructuredGrid></VTKFile>)";
}

// The value of field `name` (step `step`) at the point at `p`.
float valueAt(const mesh::UnstructuredMesh& m, const std::string& name, glm::dvec3 p,
              uint64_t step = 0) {
  const mesh::Field* f = m.findField(name);
  EXPECT_NE(f, nullptr) << name;
  for (size_t i = 0; f && i < m.points.size(); ++i)
    if (m.points[i] == p) return f->steps[step][i];
  ADD_FAILURE() << "no point there";
  return -1;
}

TEST(VtuReader, CellDataNamedAsAFieldIsAveragedOntoThePoints) {
  const std::string dir = sm::test::outputDir("VtuReader.CellData");
  auto array = [](const char* name, const char* values, int comps = 1) {
    return std::string(R"(<DataArray type="Float32" Name=")") + name + R"(" NumberOfComponents=")" +
           std::to_string(comps) + R"(" format="ascii">)" + values + "</DataArray>";
  };
  const std::string data = array("p@t0", "1 3") + array("p@t1", "10 30") +
                           array("v", "1 4 3 8", 2) + array("vtkGhostType", "0 0");
  test::writeText(dir + "/two.vtu", twoTets({"0 0 1", "0 0 -1"}, data));
  ReadOptions o;
  o.fields = {"p", "v[1]"};
  const mesh::UnstructuredMesh m = readMesh(dir + "/two.vtu", o);
  EXPECT_EQ(m.cellArrays, (std::vector<std::string>{"p", "v"}));  // by field, steps once
  EXPECT_TRUE(m.cellFields.empty());
  ASSERT_EQ(m.findField("p")->numSteps(), 2u);
  EXPECT_FLOAT_EQ(valueAt(m, "p", {0, 0, 0}), 2.0f);  // on the shared face: both cells
  EXPECT_FLOAT_EQ(valueAt(m, "p", {0, 1, 0}), 2.0f);
  EXPECT_FLOAT_EQ(valueAt(m, "p", {0, 0, 1}), 1.0f);  // one cell's apex
  EXPECT_FLOAT_EQ(valueAt(m, "p", {0, 0, -1}), 3.0f);
  EXPECT_FLOAT_EQ(valueAt(m, "p", {1, 0, 0}, 1), 20.0f);
  EXPECT_FLOAT_EQ(valueAt(m, "v[1]", {1, 0, 0}), 6.0f);
  EXPECT_FLOAT_EQ(valueAt(m, "v[1]", {0, 0, -1}), 8.0f);
  EXPECT_TRUE(std::isnan(valueAt(m, "p", {5, 5, 5})));  // in no cell: never sampled
  // Not named: listed, not read; a point array of the same name would win.
  EXPECT_EQ(readMesh(dir + "/two.vtu").fields.size(), 0u);

  // The same cells as two pieces: joined before averaging, so the shared face takes both cells.
  std::filesystem::create_directories(dir + "/p");
  test::writeText(dir + "/p/a.vtu", twoTets({"0 0 1"}, array("p", "1")));
  test::writeText(dir + "/p/b.vtu", twoTets({"0 0 -1"}, array("p", "3")));
  test::writeText(dir + "/p.pvtu", R"(<?xml version="1.0"?>
<VTKFile type="PUnstructuredGrid" version="1.0"><PUnstructuredGrid>
<Piece Source="p/a.vtu"/><Piece Source="p/b.vtu"/></PUnstructuredGrid></VTKFile>)");
  ReadOptions p;
  p.fields = {"p"};
  const mesh::UnstructuredMesh joined = readMesh(dir + "/p.pvtu", p);
  EXPECT_FLOAT_EQ(valueAt(joined, "p", {0, 0, 0}), 2.0f);
  EXPECT_FLOAT_EQ(valueAt(joined, "p", {0, 0, 1}), 1.0f);
  EXPECT_FLOAT_EQ(valueAt(joined, "p", {0, 0, -1}), 3.0f);
  EXPECT_TRUE(asksForCellData(dir + "/p.pvtu", p));
  EXPECT_FALSE(asksForCellData(dir + "/p.pvtu", ReadOptions{}));
  // Listed as readMesh loads it, also when one step is loaded (which lists the pieces' steps).
  const std::vector<FieldStepCount> listed = listFieldSteps(dir + "/p.pvtu", p);
  ASSERT_EQ(listed.size(), 1u);
  EXPECT_EQ(listed[0].name, "p");
  ReadOptions oneStep = p;
  oneStep.step = 0;
  EXPECT_FLOAT_EQ(valueAt(readMesh(dir + "/p.pvtu", oneStep), "p", {0, 0, 0}), 2.0f);
  // One step on its own is point data only: cell data needs the whole mesh. Said so.
  EXPECT_NE(
      fileErrorOf([&] { readFieldStep(dir + "/p.pvtu", "p", 0); }).find("holds 'p' as cell data"),
      std::string::npos);
  // Messages about cell data call it cell data.
  ReadOptions wide;
  wide.fields = {"v[5]"};
  EXPECT_NE(fileErrorOf([&] {
              readMesh(dir + "/two.vtu", wide);
            }).find("field 'v[5]': cell array 'v' has 2 components"),
            std::string::npos);

  const std::string fixture = fixturePath("mesh_ascii.vtu");
  EXPECT_EQ(readMesh(fixture).cellArrays, std::vector<std::string>{"quality"});
  ReadOptions other;
  other.fields = {"density"};
  // A name in no array lists the cell data beside the point arrays: the field may be there.
  EXPECT_NE(fileErrorOf([&] { readMesh(fixture, other); })
                .find("has no point or cell array 'density' (point arrays: pressure, velocity (3 "
                      "components), temp, count; cell data: quality)"),
            std::string::npos);
  EXPECT_EQ(mesh::cellArrayHint({"quality"}, "density"), "");
  EXPECT_NE(mesh::cellArrayHint({"quality", "rho"})
                .find("its cell data (quality, rho) is read when "
                      "--field names it"),
            std::string::npos);
}

TEST(VtuReader, UnknownClusterArrayListsTheCellArrays) {
  ReadOptions o;
  o.clusterArray = "rank";
  std::string msg = fileErrorOf([&] { readMesh(fixturePath("mesh_ascii.vtu"), o); });
  EXPECT_NE(msg.find("'rank'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("cluster, quality"), std::string::npos) << msg;
}

// vtkGhostType: DUPLICATECELL (1, another piece's) and HIDDENCELL (32, blanked) cells are left
// out; other flags (16: exterior) and none keep the cell. Four tetrahedra on a shared base, told
// apart by their apex point.
TEST(VtuReader, GhostCellsOwnedElsewhereOrHiddenAreSkipped) {
  const std::string path = sm::test::outputDir("VtuReader.GhostCells") + "/ghosts.vtu";
  test::writeText(path, R"(<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">
  <UnstructuredGrid>
    <Piece NumberOfPoints="7" NumberOfCells="4">
      <Points>
        <DataArray type="Float32" NumberOfComponents="3" format="ascii">
          0 0 0  1 0 0  0 1 0  0 0 1  0 0 2  0 0 3  0 0 4
        </DataArray>
      </Points>
      <Cells>
        <DataArray type="Int64" Name="connectivity" format="ascii">
          0 1 2 3  0 1 2 4  0 1 2 5  0 1 2 6
        </DataArray>
        <DataArray type="Int64" Name="offsets" format="ascii">4 8 12 16</DataArray>
        <DataArray type="UInt8" Name="types" format="ascii">10 10 10 10</DataArray>
      </Cells>
      <CellData>
        <DataArray type="UInt8" Name="vtkGhostType" format="ascii">1 32 16 0</DataArray>
      </CellData>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
)");
  test::expectGhostCellsSkipped(path, {3.0, 4.0});
}

// VTK writes LZ4 and LZMA blocks in zlib's block table; each file must read bit for bit as the zlib
// fixture of the same layout, cell data (averaged onto the points) included.
TEST(VtuReader, Lz4AndLzmaReadAsTheZlibFixture) {
  const std::pair<const char*, const char*> sameLayout[] = {
      {"mesh_lz4.vtu", "mesh_appended_raw_zlib_h64.vtu"},
      {"mesh_lzma.vtu", "mesh_binary_zlib_h64.vtu"}};
  ReadOptions o;
  o.fields = {"pressure", "velocity", "temp", "count", "quality"};
  for (const auto& [file, zlib] : sameLayout) {
    SCOPED_TRACE(file);
    const mesh::UnstructuredMesh m = readMesh(fixturePath(file), o);
    const mesh::UnstructuredMesh z = readMesh(fixturePath(zlib), o);
    ASSERT_EQ(m.fields.size(), 5u);
    EXPECT_EQ(m.points, z.points);
    EXPECT_EQ(m.cells, z.cells);
    EXPECT_EQ(test::canonicalCells(m), test::canonicalCells(z));
    for (size_t f = 0; f < m.fields.size(); ++f) {
      EXPECT_EQ(m.fields[f].name, z.fields[f].name);
      EXPECT_EQ(m.fields[f].steps, z.fields[f].steps) << m.fields[f].name;
    }
    EXPECT_EQ(m.timeValues, z.timeValues);
    EXPECT_EQ(m.cellArrays, z.cellArrays);
  }
}

TEST(VtuReader, SharedSingleCellFiles) {
  // Appended base64 + zlib, written by VTK; one cell each.
  struct Case {
    const char* file;
    CellType type;
    std::vector<uint32_t> ids;  // after orientation
    uint64_t inverted;
  };
  const Case cases[] = {{"Tetra.vtu", CellType::Tet, {0, 1, 2, 3}, 0},
                        {"Pyramid.vtu", CellType::Pyramid, {0, 1, 2, 3, 4}, 0},
                        {"Wedge.vtu", CellType::Wedge, {0, 2, 1, 3, 5, 4}, 1},
                        {"Hexahedron.vtu", CellType::Hex, {0, 1, 2, 3, 4, 5, 6, 7}, 0}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    mesh::UnstructuredMesh m = readMesh(sm::test::sharedDataPath(c.file));
    ASSERT_EQ(m.numPoints(), mesh::numVerts(c.type));
    ASSERT_EQ(m.numCells(), 1u);
    EXPECT_EQ(cellIds(m, c.type, 0), c.ids);
    EXPECT_EQ(m.invertedFixed, c.inverted);
    EXPECT_EQ(m.points[0], glm::dvec3(0, 0, 0));
    EXPECT_EQ(m.points[1], glm::dvec3(1, 0, 0));
    EXPECT_EQ(m.bounds().hi, glm::dvec3(1, 1, 1));
    EXPECT_TRUE(m.fields.empty());
  }
}

TEST(VtuReader, SharedCanFile) {
  // Appended raw, UInt64 header, Float32 points, Int64 connectivity, Exodus field data.
  mesh::UnstructuredMesh m = readMesh(sm::test::sharedDataPath("can.vtu"));
  ASSERT_EQ(m.numPoints(), 6724u);
  ASSERT_EQ(m.numCells(CellType::Hex), 4800u);
  EXPECT_EQ(m.numCells(), 4800u);
  EXPECT_EQ(m.numClusters(), 1);
  EXPECT_EQ(m.points[100], glm::dvec3(double(2.198955535888672f), double(-2.8723723888397217f),
                                      double(-14.293645858764648f)));
  EXPECT_EQ(cellIds(m, CellType::Hex, 1234),
            (std::vector<uint32_t>{2530, 2612, 2613, 2531, 2528, 2610, 2611, 2529}));
  test::expectAllPositive(m);
  // Vector fields load as magnitudes; the id arrays (GlobalIds, PedigreeIds) are left out.
  ASSERT_EQ(m.fields.size(), 3u);
  EXPECT_EQ(m.fields[0].name, "DISPL");
  EXPECT_EQ(m.fields[1].name, "VEL");
  EXPECT_EQ(m.fields[2].name, "ACCL");
  const double vx = -2702.10986328125, vy = -3059.397705078125, vz = 1261.6085205078125;
  EXPECT_FLOAT_EQ(m.fields[1].steps[0][100], float(std::sqrt(vx * vx + vy * vy + vz * vz)));
  EXPECT_TRUE(m.timeValues.empty());
  ReadOptions o;
  o.fields = {"VEL[2]", "GlobalNodeId"};
  m = readMesh(sm::test::sharedDataPath("can.vtu"), o);
  ASSERT_EQ(m.fields.size(), 2u);
  EXPECT_EQ(m.fields[0].steps[0][100], float(vz));
  EXPECT_EQ(m.fields[1].steps[0][100], 26.0f);  // as VTK reads it
}

}  // namespace
}  // namespace sm::io
