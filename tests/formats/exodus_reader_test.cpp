// The Exodus II reader on files libexodusii wrote (exodus_files.cpp): known answers for every
// block kind, blocks and decomposed files as pieces, nodal and element variables (truth table),
// time steps, and one-line errors for damaged files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include <unistd.h>

#include "common/error.h"
#include "format_files.h"
#include "format_test_util.h"
#include "io/mesh_io.h"
#include "solver_io/pieced_readers.h"

namespace sm::io {
namespace {

using mesh::CellType;
namespace fs = std::filesystem;

class ExodusReader : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = std::make_unique<test::ScratchFolder>("exodus-unit");
    dir_ = folder_->path();
    files_ = test::writeExodusFiles(dir_);
  }
  static void TearDownTestSuite() { folder_.reset(); }
  static std::string file(const std::string& name) { return dir_ + "/" + name; }
  static std::string bytesOf(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), {});
  }
  static std::string written(const std::string& name, const std::string& bytes) {
    std::ofstream(file(name), std::ios::binary) << bytes;
    return file(name);
  }
  static inline std::unique_ptr<test::ScratchFolder> folder_;
  static inline std::string dir_;
  static inline std::vector<std::string> files_;
};

using test::clustersOf;

const mesh::Field* fieldOf(const mesh::UnstructuredMesh& m, const std::string& name) {
  for (const mesh::Field& f : m.fields)
    if (f.name == name) return &f;
  return nullptr;
}

// What exodus_files.cpp writes for nodal variable "temp" (blocks.exo: scale 10; decomp: 1).
double expectedTemp(const glm::dvec3& p, int step, double perStep) {
  return p.x + 2 * p.y + 3 * p.z + perStep * step;
}

void expectFileError(const std::string& path, const ReadOptions& options, const std::string& want,
                     const std::string& naming = "") {
  try {
    readExodus(path, options);
    FAIL() << path << ": no error, wanted '" << want << "'";
  } catch (const FileError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(naming.empty() ? path : naming), std::string::npos) << what;
    EXPECT_NE(what.find(want), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST_F(ExodusReader, LayoutFromHeaders) {
  const PiecedLayout l = exodusLayout(file("blocks.exo"));
  ASSERT_EQ(l.pieces.size(), 7u);
  EXPECT_EQ(l.pieces[0], file("blocks.exo") + ", block 10 'hexes'");
  EXPECT_EQ(l.pieces[4], file("blocks.exo") + ", block 50 'quadratic'");
  EXPECT_EQ(l.pieceCells, (std::vector<uint64_t>{2, 6, 2, 1, 1, 0, 0}));
  std::vector<std::string> names;
  for (const FieldStepCount& f : l.fields) {
    names.push_back(f.name + (f.cellData ? " (cell)" : ""));
    EXPECT_EQ(f.steps, 3u);
  }
  EXPECT_EQ(names, (std::vector<std::string>{"temp", "vel_x", "vel_y", "vel_z", "pressure (cell)",
                                             "stress (cell)"}));
  EXPECT_EQ(l.times, (std::vector<double>{0, 0.5, 1.25}));
  EXPECT_EQ(l.files, std::vector<std::string>{file("blocks.exo")});

  const PiecedLayout d = exodusLayout(file("decomp.e.3.1"));
  EXPECT_EQ(d.pieces, (std::vector<std::string>{file("decomp.e.3.0"), file("decomp.e.3.1"),
                                                file("decomp.e.3.2")}));
  EXPECT_EQ(d.files, d.pieces);
  EXPECT_EQ(d.pieceCells, (std::vector<uint64_t>{4, 4, 6}));
  EXPECT_EQ(d.times, (std::vector<double>{1, 2}));
}

TEST_F(ExodusReader, BlocksOfEveryKindWithStepsAndClusters) {
  const mesh::UnstructuredMesh m = readExodus(file("blocks.exo"), {});
  EXPECT_EQ(m.numCells(CellType::Hex), 3u);  // 2 HEX8 and a HEX20 by its corners
  EXPECT_EQ(m.numCells(CellType::Tet), 6u);
  EXPECT_EQ(m.numCells(CellType::Wedge), 2u);
  EXPECT_EQ(m.numCells(CellType::Pyramid), 1u);
  EXPECT_EQ(m.skipped.surface, 2u);       // SHELL4 block
  EXPECT_EQ(m.skipped.lineOrVertex, 1u);  // BAR2 block
  EXPECT_EQ(m.skipped.quadraticReduced, 1u);
  // Blocks share nodes and weld again: 12 + 4 (tets) + 4 (wedges) + 1 (apex) + 16 (HEX20: its
  // 4 far corners and 12 mid-edge nodes).
  EXPECT_EQ(m.numPoints(), 37u);
  EXPECT_EQ(m.invertedFixed, 3u);  // the Kuhn tetrahedra written inside out; wedges are not
  EXPECT_EQ(clustersOf(m, CellType::Hex), (std::vector<int32_t>{0, 0, 4}));
  EXPECT_EQ(clustersOf(m, CellType::Tet), std::vector<int32_t>(6, 1));
  EXPECT_EQ(clustersOf(m, CellType::Wedge), (std::vector<int32_t>{2, 2}));
  EXPECT_EQ(clustersOf(m, CellType::Pyramid), std::vector<int32_t>{3});
  EXPECT_EQ(m.timeValues, (std::vector<double>{0, 0.5, 1.25}));
  EXPECT_EQ(m.cellArrays, (std::vector<std::string>{"pressure", "stress"}));
  ASSERT_EQ(m.fields.size(), 4u);
  const mesh::Field* temp = fieldOf(m, "temp");
  const mesh::Field* velY = fieldOf(m, "vel_y");
  ASSERT_TRUE(temp && velY);
  ASSERT_EQ(temp->numSteps(), 3u);
  for (int s = 0; s < 3; ++s)
    for (size_t i = 0; i < m.numPoints(); ++i) {
      EXPECT_FLOAT_EQ(temp->steps[s][i], expectedTemp(m.points[i], s, 10)) << i;
      EXPECT_FLOAT_EQ(velY->steps[s][i], -m.points[i].x) << i;
    }
}

// The same file as netCDF-4 (HDF5) with 64-bit node numbers reads as the same mesh; cut short,
// it is an error from netCDF, not a message libexodusii prints itself.
TEST_F(ExodusReader, NetCdf4WithWideIntegers) {
  const mesh::UnstructuredMesh a = readExodus(file("blocks.exo"), {});
  const mesh::UnstructuredMesh b = readExodus(file("blocks-nc4.exo"), {});
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.cells, b.cells);
  EXPECT_EQ(a.clusters, b.clusters);
  ASSERT_EQ(b.fields.size(), 4u);
  EXPECT_EQ(a.fields[0].steps, b.fields[0].steps);
  const std::string bytes = bytesOf(file("blocks-nc4.exo"));
  testing::internal::CaptureStderr();
  expectFileError(written("cut-nc4.exo", bytes.substr(0, bytes.size() / 2)), {},
                  "is a netCDF-4 (HDF5) file that netCDF cannot open");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST_F(ExodusReader, ElementVariablesFollowTheTruthTable) {
  ReadOptions o;
  o.fields = {"stress", "pressure"};
  const mesh::UnstructuredMesh m = readExodus(file("blocks.exo"), o);
  EXPECT_TRUE(m.fields.empty());
  ASSERT_EQ(m.cellFields.size(), 2u);
  const mesh::CellField& stress = m.cellFields[0];
  const mesh::CellField& pressure = m.cellFields[1];
  ASSERT_EQ(stress.name, "stress");
  ASSERT_EQ(stress.steps.size(), 3u);
  const size_t hex = mesh::typeIndex(CellType::Hex), tet = mesh::typeIndex(CellType::Tet),
               pyr = mesh::typeIndex(CellType::Pyramid);
  for (int s = 0; s < 3; ++s) {
    // Absent on the tetrahedra's block: NaN there.
    for (float v : stress.steps[s][tet]) EXPECT_TRUE(std::isnan(v));
    std::vector<float> hexes = stress.steps[s][hex];
    std::sort(hexes.begin(), hexes.end());
    EXPECT_EQ(hexes, (std::vector<float>{10 + 0.25f * s, 10 + 0.25f * s, 50 + 0.25f * s}));
    hexes = pressure.steps[s][hex];
    std::sort(hexes.begin(), hexes.end());
    EXPECT_EQ(hexes, (std::vector<float>{100.f + 1000 * s, 101.f + 1000 * s, 500.f + 1000 * s}));
    EXPECT_EQ(pressure.steps[s][pyr], std::vector<float>{400.f + 1000 * s});
    EXPECT_EQ(pressure.steps[s][tet].size(), 6u);
  }
  // Through readMesh, cell data is averaged onto the points.
  const mesh::UnstructuredMesh avg = readMesh(file("blocks.exo"), o);
  ASSERT_TRUE(fieldOf(avg, "pressure"));
  EXPECT_EQ(fieldOf(avg, "pressure")->numSteps(), 3u);
}

TEST_F(ExodusReader, OneStepAndSomePieces) {
  ReadOptions o;
  o.step = 2;
  o.fields = {"temp"};
  mesh::UnstructuredMesh m = readExodus(file("blocks.exo"), o);
  ASSERT_EQ(m.fields.size(), 1u);
  ASSERT_EQ(m.fields[0].numSteps(), 1u);
  for (size_t i = 0; i < m.numPoints(); ++i)
    EXPECT_FLOAT_EQ(m.fields[0].steps[0][i], expectedTemp(m.points[i], 2, 10));
  o.step = 9;  // past the last: the last
  m = readExodus(file("blocks.exo"), o);
  EXPECT_FLOAT_EQ(m.fields[0].steps[0][0], expectedTemp(m.points[0], 2, 10));

  ReadOptions p;
  p.pieces = {3, 1};
  m = readExodus(file("blocks.exo"), p);
  EXPECT_EQ(m.numCells(CellType::Hex), 0u);
  EXPECT_EQ(m.numCells(CellType::Tet), 6u);
  EXPECT_EQ(m.numCells(CellType::Pyramid), 1u);
  EXPECT_EQ(m.numPoints(), 8u + 5u - 2u);  // the tets and the pyramid share 2 nodes
  EXPECT_EQ(clustersOf(m, CellType::Pyramid), std::vector<int32_t>{3});
  p.pieces = {7};
  expectFileError(file("blocks.exo"), p, "has no piece 7");
}

TEST_F(ExodusReader, FieldNamesAreChecked) {
  ReadOptions o;
  o.fields = {"nope"};
  expectFileError(file("blocks.exo"), o, "has no field 'nope' (it has 'temp', 'vel_x'");
  o.fields = {"vel_x[1]"};  // components are separate scalars
  EXPECT_THROW(readExodus(file("blocks.exo"), o), FileError);
  o.fields = {"vel_z"};
  o.loadFields = false;
  EXPECT_TRUE(readExodus(file("blocks.exo"), o).fields.empty());
}

TEST_F(ExodusReader, DecomposedFilesAreOneMesh) {
  for (const char* name : {"decomp.e.3.1", "decomp.e.3.0", "decomp.e"}) {
    ReadOptions o;
    o.fields = {"temp", "rank"};
    const mesh::UnstructuredMesh m = readExodus(file(name), o);
    EXPECT_EQ(m.numCells(CellType::Hex), 10u) << name;
    EXPECT_EQ(m.numCells(CellType::Wedge), 4u);
    EXPECT_EQ(m.numPoints(), 36u);  // the 4x3x3 nodes, welded across the files
    EXPECT_EQ(m.invertedFixed, 0u);
    EXPECT_EQ(clustersOf(m, CellType::Hex), (std::vector<int32_t>{0, 0, 0, 0, 1, 1, 1, 1, 2, 2}));
    EXPECT_EQ(clustersOf(m, CellType::Wedge), std::vector<int32_t>(4, 2));
    EXPECT_EQ(m.timeValues, (std::vector<double>{1, 2}));
    ASSERT_EQ(m.fields.size(), 1u);
    ASSERT_EQ(m.fields[0].numSteps(), 2u);
    for (int s = 0; s < 2; ++s)
      for (size_t i = 0; i < m.numPoints(); ++i)
        EXPECT_FLOAT_EQ(m.fields[0].steps[s][i], expectedTemp(m.points[i], s, 1));
    ASSERT_EQ(m.cellFields.size(), 1u);
    const size_t hex = mesh::typeIndex(CellType::Hex);
    for (size_t c = 0; c < m.clusters[hex].size(); ++c)
      EXPECT_EQ(m.cellFields[0].steps[1][hex][c], m.clusters[hex][c] + 10.f);
  }
  ReadOptions one;
  one.pieces = {2};
  one.cellOrigins = true;
  const mesh::UnstructuredMesh m = readExodus(file("decomp.e.3.0"), one);
  EXPECT_EQ(m.numCells(CellType::Hex), 2u);
  EXPECT_EQ(m.numCells(CellType::Wedge), 4u);
  EXPECT_EQ(m.numPoints(), 18u);
  EXPECT_EQ(m.cellOrigin.size(), m.numCells());
}

TEST_F(ExodusReader, MissingFileOfADecomposedSet) {
  const std::string sub = file("partial");
  fs::create_directories(sub);
  for (const char* name : {"decomp.e.3.0", "decomp.e.3.2"})
    fs::copy_file(file(name), sub + "/" + name, fs::copy_options::overwrite_existing);
  expectFileError(sub + "/decomp.e.3.0", {}, "is missing", sub + "/decomp.e.3.1");
  expectFileError(sub + "/decomp.e", {}, "is missing", sub + "/decomp.e.3.1");
  expectFileError(file("decomp.e.3.3"), {}, "names file 3 of a decomposed mesh of 3");
  expectFileError(file("nothing.exo"), {}, "does not exist");
}

TEST_F(ExodusReader, DamagedFilesAreOneLineErrors) {
  expectFileError(file("badconn.exo"), {}, "block 7 'broken': element 1 refers to node 99");
  expectFileError(file("flat2d.exo"), {}, "2D mesh (num_dim 2)");
  const std::string bytes = bytesOf(file("blocks.exo"));
  expectFileError(written("half.exo", bytes.substr(0, bytes.size() / 2)), {}, "is truncated");
  expectFileError(written("short.exo", bytes.substr(0, bytes.size() - 8)), {}, "is truncated");
  expectFileError(written("header.exo", bytes.substr(0, 200)), {}, "netCDF header");
  expectFileError(written("empty.exo", ""), {}, "is not an Exodus II file");
  expectFileError(written("text.exo", "CDF\x01 not really"), {}, "netCDF header");
  // Bytes flipped anywhere: an error naming the file, or values that are merely wrong (netCDF
  // classic files have no checksums); never a crash, a hang or another exception.
  int errors = 0;
  for (int k = 1; k < 32; ++k) {
    std::string copy = bytes;
    for (size_t i = copy.size() * k / 32, n = 0; n < 12 && i < copy.size(); ++i, ++n)
      copy[i] = char(~copy[i]);
    const std::string path = written("flipped.exo", copy);
    try {
      readExodus(path, {});
    } catch (const FileError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      ++errors;
    }
  }
  EXPECT_GT(errors, 0);
}

TEST_F(ExodusReader, StopsOnRequest) {
  ReadOptions o;
  o.stopRequested = [] { return true; };
  EXPECT_THROW(readExodus(file("blocks.exo"), o), ReadStopped);
}

}  // namespace
}  // namespace sm::io
