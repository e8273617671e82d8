#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "io/mesh_io.h"
#include "io_test_util.h"
#include "support/test_support.h"

namespace sm::io {
namespace {

namespace fs = std::filesystem;
using mesh::CellType;
using test::fileErrorOf;

void expectIdentical(const mesh::UnstructuredMesh& a, const mesh::UnstructuredMesh& b) {
  EXPECT_EQ(a.points, b.points);
  for (int t = 0; t < mesh::kNumCellTypes; ++t) {
    EXPECT_EQ(a.cells[t], b.cells[t]) << "type " << t;
    EXPECT_EQ(a.clusters[t], b.clusters[t]) << "type " << t;
  }
  ASSERT_EQ(a.fields.size(), b.fields.size());
  for (size_t f = 0; f < a.fields.size(); ++f) {
    EXPECT_EQ(a.fields[f].name, b.fields[f].name);
    EXPECT_EQ(a.fields[f].steps, b.fields[f].steps) << a.fields[f].name;
  }
  EXPECT_EQ(a.timeValues, b.timeValues);
}

std::vector<std::string> tempFiles(const std::string& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string().find(".tmp.") != std::string::npos)
      found.push_back(e.path().string());
  return found;
}

TEST(VtuWriter, RoundTripIsIdentical) {
  const std::string dir = sm::test::outputDir("VtuWriter.RoundTrip");
  const mesh::UnstructuredMesh m = test::makeTestMesh(40, 5);  // arrays of several zlib blocks
  ASSERT_GT(m.points.size() * 24, 1u << 20);
  for (bool compress : {true, false}) {
    SCOPED_TRACE(compress ? "zlib" : "raw");
    const std::string path = dir + (compress ? "/zlib.vtu" : "/raw.vtu");
    writeVtu(path, m, {compress, 1});
    mesh::UnstructuredMesh r = readMesh(path);
    expectIdentical(m, r);
    EXPECT_EQ(r.invertedFixed, 0u);
    EXPECT_EQ(r.skipped.totalSkipped(), 0u);
    ReadOptions oneThread;
    oneThread.threads = 1;
    expectIdentical(m, readMesh(path, oneThread));
  }
  EXPECT_TRUE(tempFiles(dir).empty());
}

TEST(VtuWriter, FixtureMeshRoundTrip) {
  const std::string dir = sm::test::outputDir("VtuWriter.Fixture");
  mesh::UnstructuredMesh m = readMesh(test::fixturePath("mesh_ascii.vtu"));
  m.fields.push_back({"odd@t3", {m.fields[0].steps[0]}});  // one step, a name like a step's
  writeVtu(dir + "/fixture.vtu", m);
  expectIdentical(m, readMesh(dir + "/fixture.vtu"));
}

TEST(PvtuWriter, OnePiecePerClusterEachWithOnlyItsPoints) {
  const std::string dir = sm::test::outputDir("PvtuWriter.Pieces");
  fs::remove_all(dir + "/grid");
  const mesh::UnstructuredMesh m = test::makeTestMesh(12, 4);
  writePvtu(dir + "/grid.pvtu", m);
  ASSERT_EQ(countPieces(dir + "/grid.pvtu"), 4);
  for (int k = 0; k < 4; ++k) {
    const std::string piece = dir + "/grid/grid_" + std::to_string(k) + ".vtu";
    mesh::UnstructuredMesh p = readMesh(piece);
    std::set<uint32_t> used;
    for (const auto& c : p.cells) used.insert(c.begin(), c.end());
    EXPECT_EQ(used.size(), p.numPoints()) << piece;  // self-contained: no unused points
    EXPECT_EQ(p.numClusters(), k + 1);
    EXPECT_GT(p.numCells(), 0u);
  }
  // Read back together the pieces weld into the original mesh (up to point and cell order).
  mesh::UnstructuredMesh r = readMesh(dir + "/grid.pvtu");
  EXPECT_EQ(r.numPoints(), m.numPoints());
  EXPECT_EQ(test::canonicalCells(r), test::canonicalCells(m));
  EXPECT_EQ(r.timeValues, m.timeValues);
  EXPECT_EQ(r.numClusters(), 4);
  EXPECT_TRUE(tempFiles(dir).empty());
}

// Cell data written (a test mesh's fields as cell data: generate --cell-data) reads back element
// for element, from one file, from pieces and from a series of them.
TEST(PvtuWriter, CellDataRoundTrips) {
  const std::string dir = sm::test::outputDir("PvtuWriter.CellData");
  mesh::UnstructuredMesh m = test::makeTestMesh(6, 3);
  const mesh::UnstructuredMesh points = m;
  mesh::pointFieldsToCells(m);
  ASSERT_TRUE(m.fields.empty());
  ASSERT_EQ(m.cellFields.size(), 2u);  // f with one step, g with two
  ASSERT_EQ(m.cellFields[1].steps.size(), 2u);
  // Each element holds the mean of its vertices' values (a known answer, element by element).
  for (int t = 0; t < mesh::kNumCellTypes; ++t) {
    const uint32_t nv = mesh::numVerts(mesh::kAllCellTypes[t]);
    for (size_t c = 0; c < m.clusters[t].size(); ++c) {
      double sum = 0;
      for (uint32_t k = 0; k < nv; ++k)
        sum += points.fields[1].steps[1][points.cells[t][c * nv + k]];
      EXPECT_EQ(m.cellFields[1].steps[1][t][c], float(sum / nv)) << "type " << t << " cell " << c;
    }
  }
  ReadOptions cells;
  cells.fields = {"f", "g"};
  cells.cellDataOnPoints = false;
  writeVtu(dir + "/c.vtu", m);
  writePvtu(dir + "/c.pvtu", m);
  for (const char* file : {"/c.vtu", "/c.pvtu"}) {
    SCOPED_TRACE(file);
    const mesh::UnstructuredMesh r = readMesh(dir + file, cells);
    ASSERT_EQ(r.cellFields.size(), 2u);
    EXPECT_EQ(test::canonicalCells(r), test::canonicalCells(m));
  }
  // A series: a .pvtu per step, each holding that step of every field (f's only step repeats).
  writePvdSeries(dir + "/c.pvd", m);
  cells.fields = {"g"};
  const mesh::UnstructuredMesh r = readMesh(dir + "/c.pvd", cells);
  mesh::UnstructuredMesh onlyG = m;
  onlyG.cellFields.erase(onlyG.cellFields.begin());
  EXPECT_EQ(test::canonicalCells(r), test::canonicalCells(onlyG));
}

TEST(PvtuWriter, EmptyMeshGivesOneEmptyPiece) {
  const std::string dir = sm::test::outputDir("PvtuWriter.Empty");
  writePvtu(dir + "/empty.pvtu", mesh::UnstructuredMesh{});
  mesh::UnstructuredMesh r = readMesh(dir + "/empty.pvtu");
  EXPECT_EQ(r.numPoints(), 0u);
  EXPECT_EQ(r.numCells(), 0u);
}

TEST(PvtuWriter, RefusesSparseClusterIds) {
  mesh::UnstructuredMesh m = test::makeTestMesh(2, 1);
  m.clusters[mesh::typeIndex(CellType::Hex)][0] = 1 << 30;
  const std::string dir = sm::test::outputDir("PvtuWriter.Sparse");
  EXPECT_THROW(writePvtu(dir + "/sparse.pvtu", m), Error);
  EXPECT_FALSE(fs::exists(dir + "/sparse.pvtu"));
}

TEST(VtuWriter, UnwritablePathIsAFileErrorAndLeavesNothing) {
  std::string msg =
      fileErrorOf([] { writeVtu("/nonexistent-dir/x.vtu", test::makeTestMesh(2, 1)); });
  EXPECT_NE(msg.find("/nonexistent-dir/x.vtu"), std::string::npos) << msg;
  EXPECT_FALSE(fs::exists("/nonexistent-dir"));
}

// VTK's own readers (Debian's python3-vtk9) must read what we write, with no error or warning.
// A write that fails part way leaves the data set already there as it was: no piece of it
// replaced by the new mesh's, no staged files, the index still naming its own pieces.
TEST(PvtuWriter, AFailedWriteLeavesTheOldDataSetWhole) {
  const std::string dir = sm::test::outputDir("PvtuWriter.FailedWrite");
  const std::string path = dir + "/set.pvtu";
  std::filesystem::remove_all(dir + "/set");
  writePvtu(path, test::makeTestMesh(4, 1));
  const std::vector<uint8_t> oldPiece = test::readBytes(dir + "/set/set_0.vtu");
  const std::vector<uint8_t> oldIndex = test::readBytes(path);
  std::filesystem::create_directories(dir + "/set/set_2.vtu");  // where piece 2 must go
  const std::string msg = fileErrorOf([&] { writePvtu(path, test::makeTestMesh(6, 3)); });
  EXPECT_NE(msg.find("set_2.vtu: cannot write"), std::string::npos) << msg;
  EXPECT_EQ(test::readBytes(dir + "/set/set_0.vtu"), oldPiece);
  EXPECT_EQ(test::readBytes(path), oldIndex);
  EXPECT_FALSE(std::filesystem::exists(dir + "/set/set_1.vtu"));
  for (const std::string& folder : {dir, dir + "/set"})
    for (const auto& e : std::filesystem::directory_iterator(folder))
      EXPECT_EQ(e.path().string().find(".staged"), std::string::npos) << e.path();
  EXPECT_EQ(readMesh(path).numCells(), test::makeTestMesh(4, 1).numCells());
}

TEST(PvtuWriter, VtkReadsOurFiles) {
  const std::string dir = sm::test::outputDir("PvtuWriter.Vtk");
  mesh::UnstructuredMesh m = test::makeTestMesh(6, 3);
  for (auto& c : m.clusters)  // clusters 0, 1, 3: piece 2 is empty
    for (int32_t& id : c) id = id == 2 ? 3 : id;
  mesh::CellField c{"c", {{}}};  // cell data: 2 cluster + 0.5
  for (int t = 0; t < mesh::kNumCellTypes; ++t)
    for (int32_t id : m.clusters[t]) c.steps[0][t].push_back(2.0f * float(id) + 0.5f);
  m.cellFields.push_back(std::move(c));
  writePvtu(dir + "/vtk.pvtu", m, {true});
  writeVtu(dir + "/vtk.vtu", m, {false});
  const std::string script = dir + "/check.py";
  test::writeText(script, R"(import json, sys, vtk
log = vtk.vtkStringOutputWindow()
vtk.vtkOutputWindow.SetInstance(log)
out = {}
for path in sys.argv[1:3]:
    r = vtk.vtkXMLPUnstructuredGridReader() if path.endswith(".pvtu") else vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    g = r.GetOutput()
    types = {}
    for i in range(g.GetNumberOfCells()):
        types[str(g.GetCellType(i))] = types.get(str(g.GetCellType(i)), 0) + 1
    pd = g.GetPointData()
    out[path[-4:]] = {
        "points": g.GetNumberOfPoints(), "types": types,
        "arrays": {pd.GetArrayName(i): list(pd.GetArray(i).GetRange()) for i in range(pd.GetNumberOfArrays())},
        "cluster": list(g.GetCellData().GetArray("cluster").GetRange()),
        "c": list(g.GetCellData().GetArray("c").GetRange()),
        "time": [g.GetFieldData().GetArray("TimeValues").GetValue(i) for i in range(2)],
        "bounds": list(g.GetBounds())}
out["messages"] = log.GetOutput()
json.dump(out, open(sys.argv[3], "w"))
)");
  const std::string json = dir + "/vtk.json";
  fs::remove(json);
  const std::string cmd = std::string(SHELLMARCH_SYSTEM_PYTHON) + " " + script + " " + dir +
                          "/vtk.pvtu " + dir + "/vtk.vtu " + json;
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::ifstream in(json);
  nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["messages"], "");
  // The .pvtu reader appends the pieces without merging: points on cluster boundaries repeat.
  uint64_t piecePoints = 0;
  for (int k = 0; k < 4; ++k) {
    std::set<uint32_t> used;
    for (int t = 0; t < mesh::kNumCellTypes; ++t) {
      const uint32_t nv = mesh::numVerts(mesh::kAllCellTypes[t]);
      for (size_t c = 0; c < m.clusters[t].size(); ++c)
        if (m.clusters[t][c] == k)
          used.insert(m.cells[t].begin() + c * nv, m.cells[t].begin() + (c + 1) * nv);
    }
    piecePoints += used.size();
  }
  EXPECT_EQ(j["pvtu"]["points"], piecePoints);
  EXPECT_EQ(j[".vtu"]["points"], m.numPoints());
  for (const char* key : {"pvtu", ".vtu"}) {
    SCOPED_TRACE(key);
    const auto& r = j[key];
    EXPECT_EQ(r["types"]["10"], m.numCells(CellType::Tet));
    EXPECT_EQ(r["types"]["14"], m.numCells(CellType::Pyramid));
    EXPECT_EQ(r["types"]["13"], m.numCells(CellType::Wedge));
    EXPECT_EQ(r["types"]["12"], m.numCells(CellType::Hex));
    EXPECT_EQ(r["cluster"], (std::vector<double>{0, 3}));
    EXPECT_EQ(r["c"], (std::vector<double>{0.5, 6.5}));
    EXPECT_EQ(r["time"], (std::vector<double>{0, 1}));
    const mesh::Range f = mesh::fieldRange(*m.findField("f"));
    EXPECT_EQ(r["arrays"]["f"], (std::vector<double>{f.lo, f.hi}));
    const mesh::Range g1 = mesh::fieldRange(*m.findField("g"), 1);
    EXPECT_EQ(r["arrays"]["g@t1"], (std::vector<double>{g1.lo, g1.hi}));
    const mesh::Bounds b = m.bounds();
    EXPECT_EQ(r["bounds"], (std::vector<double>{b.lo.x, b.hi.x, b.lo.y, b.hi.y, b.lo.z, b.hi.z}));
  }
}

}  // namespace
}  // namespace sm::io
