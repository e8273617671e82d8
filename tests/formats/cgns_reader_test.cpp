// The CGNS reader on files libcgns wrote (cgns_files.cpp): known answers for every element kind,
// zones as pieces, fields and time steps, and one-line errors for damaged files.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>

#include "common/error.h"
#include "format_files.h"
#include "format_test_util.h"
#include "io/mesh_io.h"
#include "io_core/read_stop.h"
#include "solver_io/pieced_readers.h"

namespace sm::io {
namespace {

using mesh::CellType;
namespace fs = std::filesystem;

class CgnsReader : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = std::make_unique<test::ScratchFolder>("cgns-unit");
    dir_ = folder_->path();
    files_ = test::writeCgnsFiles(dir_);
  }
  static void TearDownTestSuite() { folder_.reset(); }
  static std::string file(const std::string& name) { return dir_ + "/" + name; }
  // A copy of `name` with `edit` applied to its bytes.
  static std::string damaged(const std::string& name, const std::string& out,
                             void (*edit)(std::string&, size_t), size_t arg) {
    std::ifstream in(file(name), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    edit(bytes, arg);
    std::ofstream(file(out), std::ios::binary) << bytes;
    return file(out);
  }
  static inline std::unique_ptr<test::ScratchFolder> folder_;
  static inline std::string dir_;
  static inline std::vector<std::string> files_;
};

using test::clustersOf;

double expectedTemperature(const glm::dvec3& p, int step) {
  return p.x + 2 * p.y + 3 * p.z + 10 * step;
}

void expectFileError(const std::string& path, const ReadOptions& options, const std::string& want) {
  try {
    readCgns(path, options);
    FAIL() << path << ": no error, wanted '" << want << "'";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

TEST_F(CgnsReader, LayoutFromHeaders) {
  const PiecedLayout l = cgnsLayout(file("mixed.cgns"));
  ASSERT_EQ(l.pieces.size(), 3u);
  EXPECT_NE(l.pieces[0].find("base 'Base' zone 'A'"), std::string::npos) << l.pieces[0];
  EXPECT_NE(l.pieces[1].find("base 'Base' zone 'B'"), std::string::npos);
  EXPECT_NE(l.pieces[2].find("base 'Base2' zone 'C'"), std::string::npos);
  EXPECT_EQ(l.pieceCells, (std::vector<uint64_t>{12, 4, 3}));
  ASSERT_EQ(l.fields.size(), 2u);
  EXPECT_EQ(l.fields[0].name, "Temperature");
  EXPECT_FALSE(l.fields[0].cellData);
  EXPECT_EQ(l.fields[0].steps, 3u);
  EXPECT_EQ(l.fields[1].name, "Pressure");
  EXPECT_TRUE(l.fields[1].cellData);
  EXPECT_EQ(l.fields[1].steps, 3u);
  EXPECT_EQ(l.times, (std::vector<double>{0, 0.5, 1.5}));
  EXPECT_EQ(l.files, std::vector<std::string>{file("mixed.cgns")});
}

TEST_F(CgnsReader, EveryElementKindZonesAndSteps) {
  const mesh::UnstructuredMesh m = readCgns(file("mixed.cgns"), {});
  EXPECT_EQ(m.numPoints(), 20u + 18u + 45u);
  EXPECT_EQ(m.numCells(CellType::Hex), 6u);
  EXPECT_EQ(m.numCells(CellType::Pyramid), 3u);
  EXPECT_EQ(m.numCells(CellType::Wedge), 3u);
  EXPECT_EQ(m.numCells(CellType::Tet), 7u);
  EXPECT_EQ(m.skipped.surface, 4u);  // the QUAD_4 wall
  EXPECT_EQ(m.skipped.quadraticReduced, 3u);
  // Every element is written in SIDS order with a positive volume, pentahedra included (their
  // first triangle faces the second, unlike a VTK wedge's): none needs fixing.
  EXPECT_EQ(m.invertedFixed, 0u);
  EXPECT_EQ(clustersOf(m, CellType::Hex), (std::vector<int32_t>{0, 1, 1, 1, 1, 2}));
  EXPECT_EQ(clustersOf(m, CellType::Pyramid), (std::vector<int32_t>{0, 0, 0}));
  EXPECT_EQ(clustersOf(m, CellType::Tet), (std::vector<int32_t>{0, 0, 0, 0, 0, 0, 2}));
  EXPECT_EQ(m.timeValues, (std::vector<double>{0, 0.5, 1.5}));
  ASSERT_EQ(m.fields.size(), 1u);  // cell data only when named
  const mesh::Field& t = m.fields[0];
  EXPECT_EQ(t.name, "Temperature");
  ASSERT_EQ(t.numSteps(), 3u);
  for (int s = 0; s < 3; ++s)  // FlowSolutionPointers order, not the file's FS2, FS0, FS1
    for (size_t i = 0; i < m.numPoints(); ++i)
      ASSERT_FLOAT_EQ(t.steps[size_t(s)][i], float(expectedTemperature(m.points[i], s)))
          << "step " << s << " point " << i;
  EXPECT_EQ(m.cellArrays, std::vector<std::string>{"Pressure"});
}

TEST_F(CgnsReader, CellCenterFieldInElementOrder) {
  ReadOptions o;
  o.fields = {"Pressure"};
  const mesh::UnstructuredMesh m = readCgns(file("mixed.cgns"), o);
  ASSERT_EQ(m.cellFields.size(), 1u);
  const auto& steps = m.cellFields[0].steps;
  ASSERT_EQ(steps.size(), 3u);
  // Zone A: hex element 1 is volume element 0; its tetrahedra are elements 7-12 (5-10).
  std::vector<float> hex = steps[1][mesh::typeIndex(CellType::Hex)];
  std::vector<float> tet = steps[1][mesh::typeIndex(CellType::Tet)];
  std::sort(hex.begin(), hex.end());
  std::sort(tet.begin(), tet.end());
  EXPECT_EQ(hex, (std::vector<float>{100, 100, 100, 101, 102, 103}));  // A, B (4), C's first
  EXPECT_EQ(tet, (std::vector<float>{101, 106, 107, 108, 109, 110, 111}));
  // The whole read averages it onto the points.
  const mesh::UnstructuredMesh avg = readMesh(file("mixed.cgns"), o);
  ASSERT_NE(avg.findField("Pressure"), nullptr);
  EXPECT_TRUE(avg.cellFields.empty());
}

TEST_F(CgnsReader, PiecesReadOnlyTheirZones) {
  ReadOptions o;
  o.pieces = {1};
  const mesh::UnstructuredMesh m = readCgns(file("mixed.cgns"), o);
  EXPECT_EQ(m.numPoints(), 18u);
  EXPECT_EQ(m.numCells(), 4u);
  EXPECT_EQ(clustersOf(m, CellType::Hex), (std::vector<int32_t>{1, 1, 1, 1}));
  EXPECT_EQ(m.skipped.surface, 0u);
  o.pieces = {3};
  expectFileError(file("mixed.cgns"), o, "");
}

TEST_F(CgnsReader, OneStep) {
  ReadOptions o;
  o.step = 2;
  const mesh::UnstructuredMesh m = readCgns(file("mixed.cgns"), o);
  ASSERT_EQ(m.fields.size(), 1u);
  ASSERT_EQ(m.fields[0].numSteps(), 1u);
  for (size_t i = 0; i < m.numPoints(); ++i)
    ASSERT_FLOAT_EQ(m.fields[0].steps[0][i], float(expectedTemperature(m.points[i], 2)));
  o.loadFields = false;
  EXPECT_TRUE(readCgns(file("mixed.cgns"), o).fields.empty());
}

TEST_F(CgnsReader, CellOriginsCountEveryElement) {
  ReadOptions o;
  o.cellOrigins = true;
  const mesh::UnstructuredMesh m = readCgns(file("mixed.cgns"), o);
  EXPECT_EQ(m.fileCells, 16u + 4u + 3u);  // zone A's boundary quads included
  ASSERT_EQ(m.cellOrigin.size(), m.numCells());
  // Zone A's hexahedron is its element 1: file cell 0.
  EXPECT_NE(std::find(m.cellOrigin.begin(), m.cellOrigin.end(), 0u), m.cellOrigin.end());
}

TEST_F(CgnsReader, StopRequestedStopsTheRead) {
  ReadOptions o;
  int asked = 0;
  o.stopRequested = [&] { return ++asked > 1; };
  EXPECT_THROW(readCgns(file("mixed.cgns"), o), ReadStopped);
}

TEST_F(CgnsReader, FieldErrorsListNames) {
  ReadOptions o;
  o.fields = {"Density"};
  expectFileError(file("mixed.cgns"), o, "'Temperature'");
}

TEST_F(CgnsReader, PolyhedraFromNface) {
  const mesh::UnstructuredMesh m = readCgns(file("poly.cgns"), {});
  EXPECT_EQ(m.numPoints(), 12u);
  EXPECT_EQ(m.skipped.polyhedraSplit, 2u);
  EXPECT_EQ(m.skipped.totalSkipped(), 0u);
  EXPECT_GE(m.numCells(), 2u);
  ASSERT_EQ(m.fields.size(), 1u);
  for (size_t i = 0; i < m.numPoints(); ++i)
    EXPECT_FLOAT_EQ(m.fields[0].steps[0][i], float(expectedTemperature(m.points[i], 0)));
}

TEST_F(CgnsReader, HigherOrderByCorners) {
  const mesh::UnstructuredMesh m = readCgns(file("higher.cgns"), {});
  EXPECT_EQ(m.numCells(CellType::Pyramid), 2u);
  EXPECT_EQ(m.numCells(CellType::Wedge), 1u);
  EXPECT_EQ(m.numCells(CellType::Hex), 1u);
  EXPECT_EQ(m.skipped.quadraticReduced, 4u);
  EXPECT_EQ(m.skipped.surface, 1u);  // the 2D base's quad
  EXPECT_EQ(cgnsLayout(file("higher.cgns")).pieces.size(), 1u);
  // The hexahedron's corners are the unit cube at x = 6.
  const auto& hex = m.cells[mesh::typeIndex(CellType::Hex)];
  for (uint32_t v : hex) EXPECT_TRUE(m.points[v].x == 6 || m.points[v].x == 7);
}

TEST_F(CgnsReader, BadInputIsOneLineError) {
  expectFileError(file("bad-vertex.cgns"), {}, "section 'Tet'");
  expectFileError(file("bad-field.cgns"), {}, "field array");  // libcgns refuses it at open
  const std::string truncated = damaged(
      "mixed.cgns", "truncated.cgns", [](std::string& b, size_t) { b.resize(b.size() / 2); }, 0);
  expectFileError(truncated, {}, "");
  expectFileError(file("missing.cgns"), {}, "");
}

// Flipped bytes anywhere: either a mesh or sm::FileError, never a crash or another exception.
// (Each a new file: HDF5 keeps a file it failed to read open, and would answer from its cache.)
TEST_F(CgnsReader, CorruptedBytesNeverCrash) {
  const uint64_t size = fs::file_size(file("mixed.cgns"));
  for (size_t k = 0; k < 64; ++k) {
    const size_t at = size_t(k * (size / 64) + 7 * k) % size_t(size);
    const std::string bad = damaged(
        "mixed.cgns", "corrupt-" + std::to_string(k) + ".cgns",
        [](std::string& b, size_t pos) {
          for (size_t i = pos; i < std::min(b.size(), pos + 8); ++i) b[i] = char(~b[i]);
        },
        at);
    try {
      readCgns(bad, {});
    } catch (const FileError& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
    fs::remove(bad);
  }
  // Files libcgns failed to read leave the library usable.
  EXPECT_EQ(readCgns(file("mixed.cgns"), {}).numCells(), 19u);
}

}  // namespace
}  // namespace sm::io
