// The SU2 reader on files gmsh wrote (gmsh_files.cpp), a two-zone file written by hand there (gmsh
// writes one zone only) and small texts.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "format_files.h"
#include "format_test_util.h"
#include "solver_io/pieced_readers.h"

namespace sm::io {
namespace {

using mesh::CellType;

std::string path(const std::string& name) {
  return test::gmshFilesFolder() + "/" + name;
}

mesh::UnstructuredMesh read(const std::string& name, const ReadOptions& options = {}) {
  const std::string p = path(name);
  return p.ends_with(".msh") ? readGmsh(FileBytes::open(p), p, options)
                             : readSu2(FileBytes::open(p), p, options);
}

mesh::UnstructuredMesh readText(const std::string& text, const ReadOptions& options = {}) {
  const auto* p = reinterpret_cast<const uint8_t*>(text.data());
  return readSu2(FileBytes::copyOf({p, text.size()}), "hand.su2", options);
}

TEST(Su2Reader, GmshWrittenFilesMatchTheirMsh) {
  for (const char* stem : {"box", "mixed", "stack"}) {
    const mesh::UnstructuredMesh s = read(std::string(stem) + ".su2");
    const mesh::UnstructuredMesh g = read(std::string(stem) + ".msh");
    EXPECT_EQ(s.cells, g.cells) << stem;  // gmsh numbers its .su2 points as its .msh nodes
    EXPECT_EQ(s.points, g.points) << stem;
    EXPECT_EQ(s.invertedFixed, 0u) << stem;
  }
  EXPECT_EQ(read("mixed.su2").numCells(CellType::Wedge), 28u);
  EXPECT_EQ(read("stack.su2").numCells(CellType::Pyramid), 1u);
}

TEST(Su2Reader, ZonesArePieces) {
  const std::string p = path("zones.su2");
  const PiecedLayout l = su2Layout(FileBytes::open(p), p);
  EXPECT_EQ(l.pieces, (std::vector<std::string>{p + ", zone 1", p + ", zone 2"}));
  EXPECT_EQ(l.pieceCells, (std::vector<uint64_t>{6, 6}));
  EXPECT_TRUE(l.fields.empty());
  const mesh::UnstructuredMesh m = read("zones.su2");
  EXPECT_EQ(m.numCells(CellType::Tet), 10u);
  EXPECT_EQ(m.points.size(), 12u);  // the 4 points of the shared face welded
  EXPECT_EQ(m.skipped.surface, 2u);
  EXPECT_EQ(m.invertedFixed, 0u);
  const auto& c = m.clusters[mesh::typeIndex(CellType::Tet)];
  EXPECT_EQ(std::count(c.begin(), c.end(), 1), 5);
  ReadOptions o;
  o.pieces = {1};
  const mesh::UnstructuredMesh z = read("zones.su2", o);
  EXPECT_EQ(z.numCells(CellType::Tet), 5u);
  EXPECT_EQ(z.bounds().lo.x, 1.0);
  for (int32_t k : z.clusters[mesh::typeIndex(CellType::Tet)]) EXPECT_EQ(k, 1);
  o.pieces = {2};
  EXPECT_THROW(read("zones.su2", o), FileError);
}

const std::string kCube =
    "% comment\nNDIME= 3\nNELEM= 2\n10 0 1 2 4\n10 1 3 2 7 1\n"
    "NPOIN= 8 8\n0 0 0\n1 0 0 1\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1 7\n"
    "NMARK= 1\nMARKER_TAG= wall\nMARKER_ELEMS= 1\n5 0 1 2\n";

using test::replaced;

void expectRefused(const std::string& text, const std::string& want) {
  test::expectFileError([&] { readText(text); }, want, "hand.su2: ");
}

TEST(Su2Reader, HandWrittenAndBadInput) {
  const mesh::UnstructuredMesh m = readText(kCube);
  EXPECT_EQ(m.numCells(CellType::Tet), 2u);
  EXPECT_EQ(m.points.size(), 8u);
  expectRefused(replaced(kCube, "NDIME= 3", "NDIME= 2"), "line 2: NDIME= 2: only 3D");
  expectRefused(replaced(kCube, "10 0 1 2 4", "10 0 1 2 44"), "");
  expectRefused(replaced(kCube, "NELEM= 2", "NELEM= 3"),
                "line 6: 'NPOIN= 8 8' after 2 of the 3 lines");
  expectRefused(replaced(kCube, "NPOIN= 8 8", "NPOIN= 9"),
                "line 15: 'NMARK= 1' after 8 of the 9 lines");
  expectRefused(replaced(kCube, "NELEM= 2", "NELEM= 99999999999"), "more lines than");
  expectRefused(replaced(kCube, "10 0 1 2 4", "11 0 1 2 4"), "type 11");
  expectRefused(replaced(kCube, "10 0 1 2 4", "10 0 1 2"), "has 3 numbers");
  expectRefused(replaced(kCube, "0 1 1\n", "0 x 1\n"), "not a coordinate");
  expectRefused("NZONE= 1\nIZONE= 2\n", "IZONE= 2");
  expectRefused("NZONE= 3\nIZONE= 1\nNDIME= 3\n", "after 1 of the 3 zones");
  expectRefused("NZONE= 3\nIZONE= 3\n", "IZONE= 3 after 1 zone(s)");
  ReadOptions o;
  o.fields = {"p"};
  EXPECT_THROW(readText(kCube, o), FileError);
}

TEST(Su2Reader, CorruptedBytesAreRefusedCleanly) {
  uint32_t seed = 54321;
  auto next = [&] { return seed = seed * 1664525u + 1013904223u; };
  for (const char* name : {"mixed.su2", "zones.su2"}) {
    std::ifstream in(path(name), std::ios::binary);
    const std::string all((std::istreambuf_iterator<char>(in)), {});
    for (int k = 0; k < 200; ++k) {
      std::string bad = all;
      for (int j = 0; j < 3; ++j) bad[next() % bad.size()] = "0123456789 \n-=%x"[next() % 17];
      try {
        readText(bad);
      } catch (const FileError&) {
      }
    }
  }
}

TEST(Su2Reader, TruncatedFilesAreRefusedCleanly) {
  for (const char* name : {"box.su2", "zones.su2"}) {
    std::ifstream in(path(name), std::ios::binary);
    const std::string all((std::istreambuf_iterator<char>(in)), {});
    for (int k = 1; k <= 20; ++k) {
      const std::string cut = all.substr(0, all.size() * k / 21);
      try {
        readText(cut);
        su2Layout(FileBytes::copyOf({reinterpret_cast<const uint8_t*>(cut.data()), cut.size()}),
                  "hand.su2");
      } catch (const FileError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("hand.su2: ", 0), 0u) << e.what();
      }
    }
  }
}

}  // namespace
}  // namespace sm::io
