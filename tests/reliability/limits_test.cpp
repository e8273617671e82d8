// Absurd declared sizes in the places tests/io/robustness_test.cpp does not reach: every loader
// must answer at once with one error that names the input, without allocating what the file
// merely claims. A replaced global operator new enforces the last point: while a test holds a
// Guard, any single request over 32 MiB throws std::bad_alloc, which counts as a failure.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>
#include <string>

#include "common/error.h"
#include "common/hash.h"
#include "common/log.h"
#include "io/mesh_io.h"
#include "prep/cache.h"
#include "scene/transfer_function.h"
#include "support/allocation_cap.h"
#include "support/test_support.h"

namespace sm {
namespace {

namespace fs = std::filesystem;

using Guard = sm::test::AllocationCap;

// The error a call gives: its message, or a test failure when it succeeds, allocates beyond the
// limit or throws anything but sm::Error.
template <typename Fn>
std::string errorOf(Fn&& fn) {
  try {
    fn();
    ADD_FAILURE() << "accepted";
  } catch (const std::bad_alloc&) {
    ADD_FAILURE() << "allocation beyond the limit (a declared size was believed)";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not an sm::Error: " << e.what();
  }
  return "";
}

std::string readError(const std::string& text, const std::string& name) {
  return errorOf([&] {
    io::readMeshFromMemory({reinterpret_cast<const uint8_t*>(text.data()), text.size()}, name);
  });
}

#define EXPECT_HAS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << (haystack)

const char* kLegacyHead =
    "# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n"
    "POINTS 4 double\n0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n";

TEST(Limits, LegacyVtkArraysDeclaringMoreThanTheFileHolds) {
  Guard guard;
  const std::string head = kLegacyHead;
  EXPECT_HAS(readError("# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n"
                       "FIELD FieldData 1\nTimeValues 1 1099511627776 double\n0 1\n",
                       "f.vtk"),
             "f.vtk: ");
  EXPECT_HAS(readError(head + "FIELD FieldData 4294967296\nTimeValues 1 1 double\n0\n", "n.vtk"),
             "n.vtk: ");
  EXPECT_HAS(readError(head + "POINT_DATA 4\nLOOKUP_TABLE t 1099511627776\n0 0 0 1\n", "l.vtk"),
             "l.vtk: ");
  EXPECT_HAS(readError(head + "POINT_DATA 4\nSCALARS s double 4096\n0 1 2 3\n", "s.vtk"),
             "s.vtk: ");
  EXPECT_HAS(readError(head + "POINT_DATA 4\nCOLOR_SCALARS c 4096\n0 1 2 3\n", "c.vtk"), "c.vtk: ");
  EXPECT_HAS(readError(head + "POINT_DATA 4\nFIELD f 1\nv 4096 4 float\n0 1 2 3\n", "v.vtk"),
             "v.vtk: ");
}

TEST(Limits, UgridFortranRecordMarkersAndCounts) {
  Guard guard;
  std::string lr8(4 + 28 + 4 + 4, '\0');
  const int32_t head = 28, counts[7] = {4, 0, 0, 1, 0, 0, 0}, huge = 0x7fffffff;
  std::memcpy(&lr8[0], &head, 4);
  std::memcpy(&lr8[4], counts, 28);
  std::memcpy(&lr8[32], &head, 4);
  std::memcpy(&lr8[36], &huge, 4);  // a grid record of 2 GiB in a 40-byte file
  EXPECT_HAS(readError(lr8, "g.lr8.ugrid"), "g.lr8.ugrid: ");
  std::string b8l(56, '\0');  // 64-bit counts near 2^63: products must not wrap into "fits"
  const int64_t big[7] = {int64_t(1) << 62, 0, 0, int64_t(1) << 61, 0, 0, 0};
  std::memcpy(b8l.data(), big, 56);
  EXPECT_HAS(readError(b8l, "g.lb8l.ugrid"), "g.lb8l.ugrid: declares");
  EXPECT_HAS(readError("4 0 0 1 0 0 4611686018427387904\n", "a.ugrid"), "a.ugrid: ");
}

// A .pvtu piece that declares 2^40 cells: the reader of that piece fails, naming it; the index
// and the other pieces are fine.
TEST(Limits, PvtuPieceDeclaringAbsurdCounts) {
  Guard guard;
  const fs::path dir = test::outputDir("Limits.Pvtu");
  const fs::path data = SHELLMARCH_IO_TEST_DATA;
  fs::create_directories(dir / "weld");
  fs::copy_file(data / "weld.pvtu", dir / "weld.pvtu", fs::copy_options::overwrite_existing);
  for (int k = 0; k < 3; ++k) {
    const std::string name = "weld_" + std::to_string(k) + ".vtu";
    fs::copy_file(data / "weld" / name, dir / "weld" / name, fs::copy_options::overwrite_existing);
  }
  std::ifstream in(dir / "weld" / "weld_1.vtu", std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  const size_t at = text.find("NumberOfCells=\"");
  ASSERT_NE(at, std::string::npos);
  text.replace(at + 15, text.find('"', at + 15) - at - 15, "1099511627776");
  std::ofstream(dir / "weld" / "weld_1.vtu", std::ios::binary) << text;
  const std::string msg = errorOf([&] { io::readMesh((dir / "weld.pvtu").string()); });
  EXPECT_HAS(msg, "weld_1.vtu: ");
  // Balancing pieces over ranks reads the headers only, and takes the claim as a weight.
  std::vector<uint64_t> counts;
  EXPECT_NO_THROW(counts = io::pieceCellCounts((dir / "weld.pvtu").string()));
  ASSERT_EQ(counts.size(), 3u);
  EXPECT_EQ(counts[1], uint64_t(1) << 40);
}

// VTK 9.4's face arrays list faces by index, so a small file can have a polyhedron name one face
// of 256 points 200 000 times: copied out as a face stream, 400 MB. Such a cell has more faces
// than any split takes (mesh::kMaxPolyhedronFaces) and is skipped as too large before any copy.
TEST(Limits, PolyhedronListingOneFaceManyTimes) {
  std::string points, ring;
  for (int i = 0; i < 256; ++i) {
    points +=
        std::to_string(std::cos(i * 0.0245)) + " " + std::to_string(std::sin(i * 0.0245)) + " 0 ";
    ring += std::to_string(i) + " ";
  }
  points += "0 0 1 1 0 1 0 1 1 0 0 2";
  std::string many;
  for (int i = 0; i < 200000; ++i) many += "0 ";
  auto array = [](const char* name, const std::string& values) {
    return std::string("<DataArray type=\"Int64\" Name=\"") + name + "\" format=\"ascii\">" +
           values + "</DataArray>";
  };
  const std::string text =
      "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\"><UnstructuredGrid><Piece "
      "NumberOfPoints=\"260\" NumberOfCells=\"2\"><Points><DataArray type=\"Float64\" "
      "NumberOfComponents=\"3\" format=\"ascii\">" +
      points + "</DataArray></Points><Cells>" + array("connectivity", ring + "256 257 258 259") +
      array("offsets", "256 260") +
      "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">42 10</DataArray>" +
      array("face_connectivity", ring) + array("face_offsets", "256") +
      array("polyhedron_to_faces", many) + array("polyhedron_offsets", "200000 200000") +
      "</Cells></Piece></UnstructuredGrid></VTKFile>";
  Guard guard;
  mesh::UnstructuredMesh m;
  try {
    m = io::readMeshFromMemory({reinterpret_cast<const uint8_t*>(text.data()), text.size()},
                               "many.vtu");
  } catch (const std::bad_alloc&) {
    FAIL() << "allocation beyond the limit (the face list was copied out)";
  }
  EXPECT_EQ(m.skipped.polyhedra, 1u);
  EXPECT_EQ(m.numCells(), 1u);  // the tetrahedron
}

// A cache whose checksum is right but whose sections claim more than it holds: a hostile or
// hand-edited file, since the writer never makes one. The checksum must not be what saves us.
TEST(Limits, CacheSectionsDeclaringMoreThanTheFileHolds) {
  Guard guard;
  for (uint64_t count : {uint64_t(1) << 40, ~uint64_t(0), uint64_t(1) << 61}) {
    std::vector<uint8_t> file(64 + 16 + 72, 0);
    std::memcpy(file.data(), "SMPREP01", 8);
    const uint32_t version = prep::kCacheFormatVersion, sections = 1, id = 1, size = 8;
    const uint64_t key = 7, payload = file.size() - 64;
    std::memcpy(&file[8], &version, 4);
    std::memcpy(&file[16], &key, 8);
    std::memcpy(&file[24], &payload, 8);
    std::memcpy(&file[40], &sections, 4);
    std::memcpy(&file[64], &id, 4);
    std::memcpy(&file[68], &size, 4);
    std::memcpy(&file[72], &count, 8);
    const uint64_t hash = hashBytes(file.data() + 64, payload);
    std::memcpy(&file[32], &hash, 8);
    prep::CacheRead r;
    try {
      r = prep::parseCache(file.data(), file.size(), key);
    } catch (const std::bad_alloc&) {
      ADD_FAILURE() << "allocated what a section claims: " << count;
    }
    EXPECT_EQ(r.status, prep::CacheStatus::Corrupt) << count;
    EXPECT_HAS(r.reason, "runs past the end");
  }
}

// JSON nests without limit; a deeply nested colour map must not exhaust the stack.
TEST(Limits, DeeplyNestedColormapJson) {
  Guard guard;
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  const std::string msg =
      errorOf([&] { scene::parseParaViewColormap("{\"RGBPoints\": " + deep + "}", "d.json"); });
  EXPECT_HAS(msg, "d.json: ");
}

}  // namespace
}  // namespace sm
