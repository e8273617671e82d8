// Stopping a read (ReadOptions::stopRequested): every format and reading path asks for the stop as
// it goes, and a stop requested at any of those checks ends the read there with io::ReadStopped,
// naming the file. The viewer relies on it to close, or jump to another step, without first
// finishing a read of a step it will not show.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <filesystem>
#include <set>

#include "io/mesh_io.h"
#include "io/vtk_binary.h"
#include "io_test_util.h"
#include "support/test_support.h"

namespace sm::io {
namespace {

using test::fixturePath;

struct Stops {
  int checks = 0;               // a read asks this often whether to stop
  std::set<std::string> named;  // the files that the stops named (a .pvtu's pieces, ...)
};

// Runs read(options) with a stop that never comes, counting the checks (n) of the second run;
// then, for each k in
// 1..n, with a stop that comes at the k-th check: the read must end with ReadStopped naming
// `file` or a file beside it (a piece, a step), after exactly k checks (one reading thread: no
// check runs beside the one that stops).
template <class Read>
Stops expectStopsAtEveryCheck(const std::string& file, Read read) {
  SCOPED_TRACE(file);
  std::atomic<int> calls{0};
  ReadOptions o;
  o.threads = 1;
  o.stopRequested = [&calls] {
    ++calls;
    return false;
  };
  read(o);  // once first: a series keeps what it learnt of its first step for the next reads
  calls = 0;
  read(o);
  const int n = calls;
  EXPECT_GT(n, 0) << "the read never asks whether to stop";
  Stops stops{n, {}};
  const std::string dir = std::filesystem::path(file).parent_path().string() + "/";
  const std::string suffix = ": reading stopped on request";
  for (int k = 1; k <= n; ++k) {
    calls = 0;
    o.stopRequested = [&calls, k] { return ++calls >= k; };
    try {
      read(o);
      ADD_FAILURE() << "a stop at check " << k << " of " << n << " did not stop the read";
    } catch (const ReadStopped& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(dir, 0), 0u) << what;
      const size_t end = what.size() - std::min(what.size(), suffix.size());
      EXPECT_EQ(what.substr(end), suffix) << what;
      stops.named.insert(what.substr(0, end));
      EXPECT_EQ(calls, k) << "the read went on past check " << k;
    }
  }
  return stops;
}

// Two tetrahedra whose point field "f" (5 values, 20 bytes) is appended raw, zlib-compressed in
// 4-byte blocks: five blocks, as a large array has thousands.
std::string smallBlocksVtu(const std::string& dir) {
  const float f[5] = {0.5f, 1.5f, 2.5f, 3.5f, 4.5f};
  const std::vector<uint8_t> blocks =
      compressBlocks(sizeof f, 4, 6, 1, [&](uint64_t at, uint64_t n, uint8_t* dst) {
        std::memcpy(dst, reinterpret_cast<const uint8_t*>(f) + at, n);
      });
  std::string text =
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\"><UnstructuredGrid>"
      "<Piece NumberOfPoints=\"5\" NumberOfCells=\"2\"><PointData>"
      "<DataArray type=\"Float32\" Name=\"f\" format=\"appended\" offset=\"0\"/></PointData>"
      "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">"
      "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1</DataArray></Points><Cells>"
      "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 2 3 1 2 3 4"
      "</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">4 8</DataArray>"
      "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">10 10</DataArray></Cells>"
      "</Piece></UnstructuredGrid><AppendedData encoding=\"raw\">_";
  text.append(reinterpret_cast<const char*>(blocks.data()), blocks.size());
  text += "</AppendedData></VTKFile>";
  const std::string path = dir + "/blocks.vtu";
  test::writeText(path, text);
  return path;
}

TEST(ReadStop, AVtuArrayStopsBetweenItsCompressedBlocks) {
  const std::string path = smallBlocksVtu(sm::test::outputDir("ReadStop.Blocks"));
  // The values are right when no stop comes (the file is what the test means it to be).
  EXPECT_EQ(readFieldStep(path, "f", 0), std::vector<float>({0.5f, 1.5f, 2.5f, 3.5f, 4.5f}));
  const Stops step =
      expectStopsAtEveryCheck(path, [&](const ReadOptions& o) { readFieldStep(path, "f", 0, o); });
  EXPECT_GE(step.checks, 5) << "fewer checks than compressed blocks";
  EXPECT_EQ(step.named, std::set<std::string>{path});
  EXPECT_GE(expectStopsAtEveryCheck(path, [&](const ReadOptions& o) { readMesh(path, o); }).checks,
            5);
}

TEST(ReadStop, EveryEncodingOfAVtuStops) {
  for (const char* file : {"mesh_ascii.vtu", "mesh_binary_zlib_h64.vtu",
                           "mesh_appended_b64_zlib_h64.vtu", "mesh_appended_raw_none_h64.vtu"}) {
    const std::string path = fixturePath(file);
    expectStopsAtEveryCheck(path, [&](const ReadOptions& o) { readFieldStep(path, "temp", 1, o); });
    expectStopsAtEveryCheck(path, [&](const ReadOptions& o) { readMesh(path, o); });
  }
}

TEST(ReadStop, APvtuStopsBetweenItsPieces) {
  const std::string path = fixturePath("weld.pvtu");
  const std::string field = readMesh(path).fields.at(0).name;
  // Every piece is stopped in: a stop names the piece it came in.
  const std::set<std::string> pieces = {fixturePath("weld/weld_0.vtu"),
                                        fixturePath("weld/weld_1.vtu"),
                                        fixturePath("weld/weld_2.vtu")};
  const Stops step = expectStopsAtEveryCheck(
      path, [&](const ReadOptions& o) { readFieldStep(path, field, 0, o); });
  EXPECT_EQ(step.named, pieces);
  const Stops whole =
      expectStopsAtEveryCheck(path, [&](const ReadOptions& o) { readMesh(path, o); });
  for (const std::string& piece : pieces) EXPECT_EQ(whole.named.count(piece), 1u) << piece;
  EXPECT_EQ(whole.named.count(path), 1u) << "no stop before the weld";
}

TEST(ReadStop, FilesReadWholeStopBetweenSections) {
  for (const char* file : {"mesh_v51_ascii.vtk", "mesh_v42_binary.vtk"}) {
    const std::string path = fixturePath(file);
    // One check per section (POINTS, CELLS, CELL_TYPES, POINT_DATA, each array, ...) at least.
    EXPECT_GE(expectStopsAtEveryCheck(
                  path, [&](const ReadOptions& o) { readFieldStep(path, "temp", 2, o); })
                  .checks,
              5);
  }
  const std::string ugrid = sm::test::outputDir("ReadStop.Ugrid") + "/tet.ugrid";
  test::writeText(ugrid, "4 0 0 1 0 0 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 2 3 4\n");
  ASSERT_EQ(readMesh(ugrid).numCells(), 1u);
  EXPECT_GE(
      expectStopsAtEveryCheck(ugrid, [&](const ReadOptions& o) { readMesh(ugrid, o); }).checks, 2);
}

TEST(ReadStop, ASeriesStopsInEachStepsFile) {
  const std::string dir = sm::test::outputDir("ReadStop.Series");
  test::writeText(dir + "/a.vtk", test::legacyTwoTets(1.0f));
  test::writeText(dir + "/b.vtk", test::legacyTwoTets(2.0f));
  const std::string pvd = test::twoStepSeries(dir, "s.pvd", "a.vtk", "b.vtk");
  // A step's read stops in its own file; a whole read of the series, in each step's.
  EXPECT_EQ(
      expectStopsAtEveryCheck(pvd, [&](const ReadOptions& o) { readFieldStep(pvd, "f", 1, o); })
          .named.count(dir + "/b.vtk"),
      1u);
  const Stops whole = expectStopsAtEveryCheck(pvd, [&](const ReadOptions& o) { readMesh(pvd, o); });
  EXPECT_EQ(whole.named.count(dir + "/a.vtk"), 1u);
  EXPECT_EQ(whole.named.count(dir + "/b.vtk"), 1u);
}

TEST(ReadStop, CellDataStepsStopToo) {
  const std::string dir = sm::test::outputDir("ReadStop.Cells");
  test::writeText(dir + "/a.vtu", test::twoTets(1.0f, 2.0f));
  const std::string path = dir + "/a.vtu";
  ReadOptions o;
  o.fields = {"p"};
  expectStopsAtEveryCheck(path, [&](const ReadOptions& s) {
    ReadOptions r = s;
    r.fields = o.fields;
    readCellFieldStep(path, "p", 0, r);
  });
}

TEST(ReadStop, IsNotAFileError) {
  // Nothing is wrong with the file: callers that report FileErrors must not report a stop.
  const std::string path = fixturePath("mesh_ascii.vtu");
  ReadOptions o;
  o.stopRequested = [] { return true; };
  try {
    readMesh(path, o);
    ADD_FAILURE() << "not stopped";
  } catch (const Error& e) {
    ADD_FAILURE() << "a stop thrown as an error: " << e.what();
  } catch (const ReadStopped&) {
  }
}

}  // namespace
}  // namespace sm::io
