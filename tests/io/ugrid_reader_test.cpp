#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "io/mesh_io.h"
#include "io_test_util.h"
#include "support/test_support.h"

namespace sm::io {
namespace {

using mesh::CellType;
using test::cellIds;
using test::fileErrorOf;

// A grid whose elements have known geometry, in UGRID node order (1-based):
//   pyramid: base square A(0,0,0) B(1,0,0) C(1,1,0) D(0,1,0), apex E(0.5,0.5,1). UGRID puts the
//            base on nodes 1 2 5 4 and the apex on node 3, wound so that base 1 2 5 4 faces away
//            from the apex: A D E B C.
//   prism:   triangle P(2,0,0) Q(3,0,0) R(2,1,0) below P' Q' R' at z = 1; UGRID winds 1 2 3
//            towards 4 5 6: P Q R P' Q' R'.
//   tetra:   (5,0,0) (6,0,0) (5,1,0) (5,0,1); hexahedron: unit cube at x = 8 in VTK order.
// Plus one boundary triangle and one boundary quad (skipped as 2D cells).
struct Grid {
  std::vector<double> xyz = {
      0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, 1,           // A B C D E
      2, 0, 0, 3, 0, 0, 2, 1, 0, 2, 0, 1, 3,   0,   1, 2, 1, 1,  // P Q R P' Q' R'
      5, 0, 0, 6, 0, 0, 5, 1, 0, 5, 0, 1,                        // tetra
      8, 0, 0, 9, 0, 0, 9, 1, 0, 8, 1, 0, 8,   0,   1, 9, 0, 1, 9, 1, 1, 8, 1, 1};
  std::vector<int64_t> tris = {1, 2, 5}, quads = {1, 2, 3, 4}, tags = {7, 8};
  std::vector<int64_t> tets = {12, 13, 14, 15}, pyrs = {1, 4, 5, 2, 3},
                       prisms = {6, 7, 8, 9, 10, 11};
  std::vector<int64_t> hexes = {16, 17, 18, 19, 20, 21, 22, 23};
  int64_t nodes() const { return int64_t(xyz.size() / 3); }
  std::vector<int64_t> counts() const {
    return {nodes(),
            int64_t(tris.size() / 3),
            int64_t(quads.size() / 4),
            int64_t(tets.size() / 4),
            int64_t(pyrs.size() / 5),
            int64_t(prisms.size() / 6),
            int64_t(hexes.size() / 8)};
  }
  std::vector<int64_t> ints() const {
    std::vector<int64_t> all;
    for (const auto* v : {&tris, &quads, &tags, &tets, &pyrs, &prisms, &hexes})
      all.insert(all.end(), v->begin(), v->end());
    return all;
  }
};

struct Variant {
  const char* suffix;
  bool big, fortran;
  int intSize, realSize;
};

template <class T>
void put(std::vector<uint8_t>& out, T v, bool big) {
  if (big != (std::endian::native == std::endian::big)) {
    uint8_t b[sizeof(T)];
    std::memcpy(b, &v, sizeof v);
    std::reverse(b, b + sizeof(T));
    std::memcpy(&v, b, sizeof v);
  }
  const uint8_t* p = reinterpret_cast<const uint8_t*>(&v);
  out.insert(out.end(), p, p + sizeof(T));
}

void putInt(std::vector<uint8_t>& out, int64_t v, const Variant& f) {
  if (f.intSize == 8)
    put<int64_t>(out, v, f.big);
  else
    put<int32_t>(out, int32_t(v), f.big);
}

std::vector<uint8_t> encode(const Grid& g, const Variant& f) {
  std::vector<uint8_t> head, body, out;
  for (int64_t c : g.counts()) putInt(head, c, f);
  for (double x : g.xyz)
    f.realSize == 8 ? put<double>(body, x, f.big) : put<float>(body, float(x), f.big);
  for (int64_t i : g.ints()) putInt(body, i, f);
  auto record = [&](const std::vector<uint8_t>& r) {
    if (f.fortran) put<int32_t>(out, int32_t(r.size()), f.big);
    out.insert(out.end(), r.begin(), r.end());
    if (f.fortran) put<int32_t>(out, int32_t(r.size()), f.big);
  };
  record(head);
  record(body);
  return out;
}

std::string ascii(const Grid& g) {
  std::ostringstream s;
  for (int64_t c : g.counts()) s << c << " ";
  s << "\n";
  for (size_t i = 0; i < g.xyz.size(); ++i) s << g.xyz[i] << (i % 3 == 2 ? "\n" : " ");
  for (int64_t i : g.ints()) s << i << "\n";
  return s.str();
}

void expectKnownGrid(const mesh::UnstructuredMesh& m) {
  ASSERT_EQ(m.numPoints(), 23u);
  EXPECT_EQ(m.points[4], glm::dvec3(0.5, 0.5, 1));
  ASSERT_EQ(m.numCells(CellType::Pyramid), 1u);
  ASSERT_EQ(m.numCells(CellType::Wedge), 1u);
  ASSERT_EQ(m.numCells(CellType::Tet), 1u);
  ASSERT_EQ(m.numCells(CellType::Hex), 1u);
  // The ordering proof: VTK wants the base D A B C (a cycle of the square, wound towards the
  // apex) and the apex E last. Reading UGRID's A D E B C without the permutation would put the
  // apex in the base and the builder would see a twisted cell; mirroring it would show up as an
  // inverted cell.
  EXPECT_EQ(cellIds(m, CellType::Pyramid, 0), (std::vector<uint32_t>{3, 0, 1, 2, 4}));
  EXPECT_EQ(m.points[cellIds(m, CellType::Pyramid, 0)[4]], glm::dvec3(0.5, 0.5, 1));
  // VTK winds triangle 0 1 2 away from 3 4 5: Q P R over Q' P' R'.
  EXPECT_EQ(cellIds(m, CellType::Wedge, 0), (std::vector<uint32_t>{6, 5, 7, 9, 8, 10}));
  EXPECT_EQ(cellIds(m, CellType::Tet, 0), (std::vector<uint32_t>{11, 12, 13, 14}));
  EXPECT_EQ(cellIds(m, CellType::Hex, 0), (std::vector<uint32_t>{15, 16, 17, 18, 19, 20, 21, 22}));
  EXPECT_EQ(m.invertedFixed, 0u) << "a correctly wound UGRID element must not need fixing";
  EXPECT_EQ(m.skipped.surface, 2u);
  EXPECT_EQ(m.numClusters(), 1);
  test::expectAllPositive(m);
}

const Variant kVariants[] = {{"b8", true, false, 4, 8},  {"lb8", false, false, 4, 8},
                             {"b8l", true, false, 8, 8}, {"lb8l", false, false, 8, 8},
                             {"b4", true, false, 4, 4},  {"lb4", false, false, 4, 4},
                             {"r8", true, true, 4, 8},   {"lr8", false, true, 4, 8},
                             {"r4", true, true, 4, 4},   {"lr4", false, true, 4, 4}};

TEST(UgridReader, EveryBinaryVariantGivesTheKnownElements) {
  const std::string dir = sm::test::outputDir("UgridReader.Variants");
  for (const Variant& v : kVariants) {
    SCOPED_TRACE(v.suffix);
    const std::string path = dir + "/grid." + v.suffix + ".ugrid";
    test::writeBytes(path, encode(Grid{}, v));
    expectKnownGrid(readMesh(path));
  }
}

TEST(UgridReader, AsciiGivesTheKnownElements) {
  const std::string path = sm::test::outputDir("UgridReader.Ascii") + "/grid.ugrid";
  test::writeText(path, ascii(Grid{}));
  expectKnownGrid(readMesh(path));
}

TEST(UgridReader, WrongSuffixIsNotSilentlyMisread) {
  const std::string dir = sm::test::outputDir("UgridReader.WrongSuffix");
  test::writeBytes(dir + "/grid.ugrid", encode(Grid{}, kVariants[1]));  // binary named as ascii
  std::string msg = fileErrorOf([&] { readMesh(dir + "/grid.ugrid"); });
  EXPECT_NE(msg.find(".lb8.ugrid"), std::string::npos) << msg;
  test::writeBytes(dir + "/grid.b8.ugrid", encode(Grid{}, kVariants[1]));  // little as big-endian
  msg = fileErrorOf([&] { readMesh(dir + "/grid.b8.ugrid"); });
  EXPECT_NE(msg.find("grid.b8.ugrid"), std::string::npos) << msg;
  test::writeBytes(dir + "/grid.lr8.ugrid", encode(Grid{}, kVariants[1]));  // C stream as Fortran
  msg = fileErrorOf([&] { readMesh(dir + "/grid.lr8.ugrid"); });
  EXPECT_NE(msg.find("Fortran record marker"), std::string::npos) << msg;
}

TEST(UgridReader, NodeNumbersOutOfRangeAreErrors) {
  const std::string dir = sm::test::outputDir("UgridReader.OutOfRange");
  for (int64_t bad : {0, 24}) {
    Grid g;
    g.hexes[3] = bad;
    test::writeBytes(dir + "/bad.lb8.ugrid", encode(g, kVariants[1]));
    std::string msg = fileErrorOf([&] { readMesh(dir + "/bad.lb8.ugrid"); });
    EXPECT_NE(msg.find("refers to node " + std::to_string(bad)), std::string::npos) << msg;
    EXPECT_NE(msg.find("1 to 23"), std::string::npos) << msg;
  }
}

void writeFloats(const std::string& path, const std::vector<float>& v) {
  std::vector<uint8_t> b;
  for (float x : v) put<float>(b, x, false);
  test::writeBytes(path, b);
}

TEST(UgridReader, FieldsFromSideFiles) {
  const std::string dir = sm::test::outputDir("UgridReader.SideFiles");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  test::writeBytes(dir + "/wing.lb8.ugrid", encode(Grid{}, kVariants[1]));
  std::vector<float> p(23), t0(23), t1(23);
  for (int i = 0; i < 23; ++i) {
    p[i] = 0.5f * i;
    t0[i] = float(i);
    t1[i] = 100.0f + i;
  }
  writeFloats(dir + "/wing.pressure.f32", p);
  writeFloats(dir + "/wing.temp.0.f32", t0);
  writeFloats(dir + "/wing.temp.1.f32", t1);
  writeFloats(dir + "/other.pressure.f32", std::vector<float>(5));  // another grid's: ignored
  // A grid whose stem extends this one's owns the side files named after it ("wing.fine.mach"
  // is not a field "fine.mach" of "wing").
  test::writeBytes(dir + "/wing.fine.b8.ugrid", encode(Grid{}, kVariants[0]));
  writeFloats(dir + "/wing.fine.mach.f32", std::vector<float>(7));
  mesh::UnstructuredMesh m = readMesh(dir + "/wing.lb8.ugrid");
  ASSERT_EQ(m.fields.size(), 2u);
  const mesh::Field* fp = m.findField("pressure");
  const mesh::Field* ft = m.findField("temp");
  ASSERT_TRUE(fp && ft);
  EXPECT_EQ(fp->steps[0], p);
  ASSERT_EQ(ft->numSteps(), 2u);
  EXPECT_EQ(ft->steps[1], t1);
  ReadOptions o;
  o.fields = {"temp"};
  EXPECT_EQ(readMesh(dir + "/wing.lb8.ugrid", o).fields.size(), 1u);
  o.fields = {"density"};
  std::string msg = fileErrorOf([&] { readMesh(dir + "/wing.lb8.ugrid", o); });
  EXPECT_NE(msg.find("pressure, temp"), std::string::npos) << msg;
  // A side file of the wrong size names itself.
  writeFloats(dir + "/wing.temp.1.f32", std::vector<float>(22));
  msg = fileErrorOf([&] { readMesh(dir + "/wing.lb8.ugrid"); });
  EXPECT_NE(msg.find("wing.temp.1.f32"), std::string::npos) << msg;
  EXPECT_NE(msg.find("88 bytes"), std::string::npos) << msg;
  // A missing step is an error too.
  std::filesystem::remove(dir + "/wing.temp.1.f32");
  writeFloats(dir + "/wing.temp.2.f32", t1);
  msg = fileErrorOf([&] { readMesh(dir + "/wing.lb8.ugrid"); });
  EXPECT_NE(msg.find("time step 1"), std::string::npos) << msg;
  // Zero-padded step numbers, as solvers write them, are the same steps.
  std::filesystem::remove(dir + "/wing.temp.2.f32");
  std::filesystem::remove(dir + "/wing.temp.0.f32");
  writeFloats(dir + "/wing.temp.0000.f32", t0);
  writeFloats(dir + "/wing.temp.0001.f32", t1);
  m = readMesh(dir + "/wing.lb8.ugrid");
  ft = m.findField("temp");
  ASSERT_TRUE(ft);
  ASSERT_EQ(ft->numSteps(), 2u);
  EXPECT_EQ(ft->steps[0], t0);
  EXPECT_EQ(ft->steps[1], t1);
}

TEST(UgridReader, ClusterArraysDoNotExist) {
  const std::string path = sm::test::outputDir("UgridReader.Clusters") + "/grid.lb8.ugrid";
  test::writeBytes(path, encode(Grid{}, kVariants[1]));
  ReadOptions o;
  o.clusterArray = "cluster";
  std::string msg = fileErrorOf([&] { readMesh(path, o); });
  EXPECT_NE(msg.find("no cell array 'cluster'"), std::string::npos) << msg;
}

}  // namespace
}  // namespace sm::io
