// The Gmsh reader on files gmsh itself wrote (gmsh_files.cpp) and on small hand-written texts.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <glm/geometric.hpp>

#include "common/error.h"
#include "format_files.h"
#include "format_test_util.h"
#include "solver_io/gmsh_sections.h"
#include "solver_io/pieced_readers.h"

namespace sm::test {
std::vector<std::array<int, 3>> gmshElementTable();  // gmsh_files.cpp
}

namespace sm::io {
namespace {

using mesh::CellType;

std::string path(const std::string& name) {
  return test::gmshFilesFolder() + "/" + name;
}

mesh::UnstructuredMesh read(const std::string& name, const ReadOptions& options = {}) {
  return readGmsh(FileBytes::open(path(name)), path(name), options);
}

mesh::UnstructuredMesh readText(const std::string& text, const ReadOptions& options = {}) {
  const auto* p = reinterpret_cast<const uint8_t*>(text.data());
  return readGmsh(FileBytes::copyOf({p, text.size()}), "hand.msh", options);
}

const mesh::Field& field(const mesh::UnstructuredMesh& m, const std::string& name) {
  for (const mesh::Field& f : m.fields)
    if (f.name == name) return f;
  throw std::runtime_error("no field " + name);
}

double temperature(const glm::dvec3& p, int step) {
  return p.x + 2 * p.y + 3 * p.z + step;
}

TEST(GmshReader, ElementTableIsGmshs) {
  const auto table = test::gmshElementTable();
  for (int type = 1; type <= 140; ++type) {
    const GmshElementType t = gmshElementType(type);
    const auto& g = table[type - 1];
    if (t.dim < 0) continue;  // refused types: polygons, polyhedra, order 0
    EXPECT_EQ(t.dim, g[0]) << type;
    EXPECT_EQ(int(t.nodes), g[1]) << type;
    EXPECT_EQ(int(t.corners), g[2]) << type;
  }
  for (int type : {4, 5, 6, 7, 11, 12, 13, 14, 17, 18, 19, 29, 30, 92, 118})
    EXPECT_EQ(gmshElementType(type).dim, 3) << type;
}

TEST(GmshReader, AsciiCountsFieldsStepsAndTimes) {
  const mesh::UnstructuredMesh m = read("box.msh");
  EXPECT_EQ(m.points.size(), 339u);
  EXPECT_EQ(m.numCells(CellType::Tet), 1125u);
  EXPECT_EQ(m.skipped.surface, 540u);
  EXPECT_EQ(m.skipped.lineOrVertex, 80u);
  EXPECT_EQ(m.invertedFixed, 0u);
  EXPECT_EQ(m.timeValues, (std::vector<double>{0, 0.5, 1}));
  const mesh::Field& t = field(m, "temperature");
  ASSERT_EQ(t.numSteps(), 3u);
  for (int k = 0; k < 3; ++k)
    for (size_t i = 0; i < m.points.size(); ++i)
      ASSERT_NEAR(t.steps[k][i], temperature(m.points[i], k), 1e-5);
  const mesh::Field& v = field(m, "velocity");
  for (size_t i = 0; i < m.points.size(); ++i)
    ASSERT_NEAR(v.steps[0][i], glm::length(m.points[i]), 1e-5);
  const PiecedLayout l = gmshLayout(FileBytes::open(path("box.msh")), path("box.msh"));
  EXPECT_EQ(l.pieces, std::vector<std::string>{path("box.msh")});
  EXPECT_EQ(l.pieceCells, std::vector<uint64_t>{1125});
  ASSERT_EQ(l.fields.size(), 3u);
  EXPECT_EQ(l.fields[2].name, "pressure");
  EXPECT_TRUE(l.fields[2].cellData);
  EXPECT_EQ(l.fields[2].steps, 2u);
  EXPECT_EQ(l.fields[1].components, 3u);
}

TEST(GmshReader, BinaryReadsAsAscii) {
  for (const auto& [a, b] :
       {std::pair{"box.msh", "box-binary.msh"}, std::pair{"box-part.msh", "box-part-binary.msh"}}) {
    // Gmsh prints coordinates with 16 digits, one short of a double's round trip: the ASCII
    // file's points may differ from the binary file's in the last bit.
    const mesh::UnstructuredMesh x = read(a), y = read(b);
    ASSERT_EQ(x.points.size(), y.points.size()) << b;
    for (size_t i = 0; i < x.points.size(); ++i)
      ASSERT_LT(glm::length(x.points[i] - y.points[i]), 1e-15) << b << " point " << i;
    EXPECT_TRUE(x.cells == y.cells) << b;
    EXPECT_TRUE(x.clusters == y.clusters) << b;
    ASSERT_EQ(x.fields.size(), y.fields.size());
    for (size_t f = 0; f < x.fields.size(); ++f)
      for (size_t k = 0; k < x.fields[f].numSteps(); ++k)
        for (size_t i = 0; i < x.points.size(); ++i)
          ASSERT_NEAR(x.fields[f].steps[k][i], y.fields[f].steps[k][i], 1e-6) << b;
  }
}

TEST(GmshReader, PartitionsArePieces) {
  const std::string p = path("box-part.msh");
  const PiecedLayout l = gmshLayout(FileBytes::open(p), p);
  ASSERT_EQ(l.pieces.size(), 3u);
  EXPECT_EQ(l.pieces[2], p + ", partition 3");
  EXPECT_EQ(l.pieceCells[0] + l.pieceCells[1] + l.pieceCells[2], 1125u);
  const mesh::UnstructuredMesh all = read("box-part.msh");
  EXPECT_EQ(all.numCells(CellType::Tet), 1125u);
  EXPECT_EQ(all.points.size(), 339u);  // welded across partitions
  std::array<uint64_t, 3> perCluster{};
  for (int32_t c : all.clusters[mesh::typeIndex(CellType::Tet)]) ++perCluster.at(c);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(perCluster[k], l.pieceCells[k]);
  ReadOptions one;
  one.pieces = {1};
  const mesh::UnstructuredMesh m = read("box-part.msh", one);
  EXPECT_EQ(m.numCells(CellType::Tet), l.pieceCells[1]);
  for (int32_t c : m.clusters[mesh::typeIndex(CellType::Tet)]) ASSERT_EQ(c, 1);
  const mesh::Field& t = field(m, "temperature");
  for (size_t i = 0; i < m.points.size(); ++i)
    ASSERT_NEAR(t.steps[2][i], temperature(m.points[i], 2), 1e-5);
  one.pieces = {3};
  EXPECT_THROW(read("box-part.msh", one), FileError);
}

TEST(GmshReader, StepComponentAndCellData) {
  ReadOptions o;
  o.step = 1;
  o.fields = {"temperature", "velocity[1]", "pressure"};
  const mesh::UnstructuredMesh m = read("box-binary.msh", o);
  EXPECT_EQ(m.timeValues, (std::vector<double>{0, 0.5, 1}));  // every step's time, as series keep
  ASSERT_EQ(field(m, "temperature").numSteps(), 1u);
  for (size_t i = 0; i < m.points.size(); ++i) {
    ASSERT_NEAR(field(m, "temperature").steps[0][i], temperature(m.points[i], 1), 1e-5);
    ASSERT_NEAR(field(m, "velocity[1]").steps[0][i], m.points[i].y, 1e-6);
  }
  ASSERT_EQ(m.cellFields.size(), 1u);
  ASSERT_EQ(m.cellFields[0].steps.size(), 1u);
  // Pressure is element tag + step; gmsh numbers the tetrahedra after the 620 lower elements.
  const auto& tets = m.cellFields[0].steps[0][mesh::typeIndex(CellType::Tet)];
  ASSERT_EQ(tets.size(), 1125u);
  EXPECT_FLOAT_EQ(tets[0], 621 + 1);
  o = {};
  o.cellOrigins = true;
  const mesh::UnstructuredMesh c = read("box-part.msh", o);
  EXPECT_EQ(c.cellOrigin.size(), 1125u);
  EXPECT_EQ(c.fileCells, 1125u + 793u);  // the partitions' elements, surfaces and lines included
  o.stopRequested = [] { return true; };
  EXPECT_THROW(read("box.msh", o), ReadStopped);
  o = {};
  o.fields = {"nothing"};
  EXPECT_THROW(read("box.msh", o), FileError);
}

TEST(GmshReader, HigherOrderReducedToCornersAndMixedTypes) {
  const mesh::UnstructuredMesh q = read("box-order2.msh"), l = read("box.msh");
  EXPECT_EQ(q.numCells(CellType::Tet), 1125u);
  EXPECT_EQ(q.skipped.quadraticReduced, 1125u);
  const mesh::UnstructuredMesh m = read("mixed.msh"), m2 = read("mixed-order2.msh");
  for (const auto* x : {&m, &m2}) {
    EXPECT_EQ(x->numCells(CellType::Wedge), 28u);
    EXPECT_EQ(x->numCells(CellType::Hex), 8u);
    EXPECT_EQ(x->invertedFixed, 0u);  // gmsh's prisms mirrored into VTK's wedges
  }
  EXPECT_EQ(m2.skipped.quadraticReduced, 36u);
  const mesh::UnstructuredMesh s = read("stack.msh");
  EXPECT_EQ(s.numCells(CellType::Pyramid), 1u);
  EXPECT_EQ(s.numCells(CellType::Hex), 1u);
  EXPECT_EQ(s.numCells(CellType::Tet), 1u);
  EXPECT_EQ(s.invertedFixed, 0u);
}

// A cut file is read or refused with a FileError naming it, never a crash.
TEST(GmshReader, TruncatedFilesAreRefusedCleanly) {
  for (const char* name : {"box.msh", "box-binary.msh", "box-part-binary.msh", "mixed.msh"}) {
    std::ifstream in(path(name), std::ios::binary);
    const std::string all((std::istreambuf_iterator<char>(in)), {});
    for (int k = 1; k <= 20; ++k) {
      const std::string cut = all.substr(0, all.size() * k / 21);
      try {
        readText(cut);
      } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("hand.msh"), std::string::npos) << e.what();
      }
      try {
        readGmsh(FileBytes::copyOf({reinterpret_cast<const uint8_t*>(cut.data()), cut.size()}),
                 "hand.msh", {});
        gmshLayout(FileBytes::copyOf({reinterpret_cast<const uint8_t*>(cut.data()), cut.size()}),
                   "hand.msh");
      } catch (const FileError&) {
      }
    }
  }
}

// Random bytes changed (a crude fuzzer, deterministic): read or FileError, never a crash.
TEST(GmshReader, CorruptedBytesAreRefusedCleanly) {
  uint32_t seed = 12345;
  auto next = [&] { return seed = seed * 1664525u + 1013904223u; };
  for (const char* name : {"box-binary.msh", "box-part-binary.msh", "mixed.msh", "stack.msh"}) {
    std::ifstream in(path(name), std::ios::binary);
    const std::string all((std::istreambuf_iterator<char>(in)), {});
    for (int k = 0; k < 100; ++k) {
      std::string bad = all;
      for (int j = 0; j < 4; ++j) bad[next() % bad.size()] = char(next() >> 24);
      try {
        ReadOptions o;
        o.fields = {"temperature", "pressure"};
        if (std::string(name).starts_with("stack")) o.fields.clear();
        readText(bad, o);
      } catch (const FileError&) {
      }
    }
  }
}

const std::string kTwoTets =
    "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
    "$Nodes\n1 5 1 5\n3 1 0 5\n1\n2\n3\n4\n5\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n$EndNodes\n"
    "$Elements\n1 2 1 2\n3 1 4 2\n1 1 2 3 4\n2 2 3 4 5\n$EndElements\n";

using test::replaced;

void expectRefused(const std::string& text, const std::string& want) {
  test::expectFileError([&] { readText(text); }, want, "hand.msh: ");
}

TEST(GmshReader, HandWrittenAndBadInput) {
  EXPECT_EQ(readText(kTwoTets).numCells(CellType::Tet), 2u);
  expectRefused(replaced(kTwoTets, "2 2 3 4 5", "2 2 3 4 9"),
                "line 22: element 2 of entity 1 refers to node 9");
  expectRefused(replaced(kTwoTets, "1 5 1 5", "1 6 1 5"), "more nodes than its blocks");
  expectRefused(replaced(kTwoTets, "3 1 4 2", "3 1 4 3"), "line");
  expectRefused(replaced(kTwoTets, "3 1 4 2", "3 1 200 2"), "element type 200");
  expectRefused(replaced(kTwoTets, "4.1 0 8", "2.2 0 8"), "only version 4.1 is read");
  expectRefused(replaced(kTwoTets, "1 5 1 5", "1 99999999999 1 5"), "more than the");
  expectRefused(replaced(kTwoTets, "4.1 0 8\n", std::string("4.1 1 8\n\x02\0\0\0\n", 13)),
                "endianness marker is 2");
  expectRefused("solid x\nendsolid\n", "");
  ReadOptions o;
  o.fields = {"p"};
  EXPECT_THROW(readText(kTwoTets, o), FileError);
}

}  // namespace
}  // namespace sm::io
