// Time series written one file per step (.pvd, .series): read back as one mesh whose fields have a
// step per file in time order, with the steps' times; one step alone; the streaming calls; cell
// data; and every malformed index named by file. Steps that are not the same mesh or data:
// series_checks_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "io/mesh_io.h"
#include "io_test_util.h"
#include "support/test_support.h"

namespace sm::io {
namespace {

namespace fs = std::filesystem;
using test::fileErrorOf;
using test::legacyTwoTets;
using test::twoTets;
using test::writeText;

// makeTestMesh with a third field of three steps and uneven times.
mesh::UnstructuredMesh threeSteps() {
  mesh::UnstructuredMesh m = test::makeTestMesh(3, 2);
  mesh::Field h{"h", {}};
  for (int s = 0; s < 3; ++s) {
    std::vector<float> v(m.numPoints());
    for (size_t i = 0; i < v.size(); ++i) v[i] = float(m.points[i].x * (s + 1) - m.points[i].z);
    h.steps.push_back(std::move(v));
  }
  m.fields.push_back(std::move(h));
  m.timeValues = {0.0, 0.25, 1.5};
  return m;
}

// Step k of every field: a field with fewer steps repeats its last.
std::vector<float> stepOf(const mesh::Field& f, size_t k) {
  return f.steps[std::min(k, f.steps.size() - 1)];
}

TEST(Series, PvdRoundTripGivesEveryStepInTimeOrder) {
  const std::string dir = sm::test::outputDir("Series.PvdRoundTrip");
  const mesh::UnstructuredMesh m = threeSteps();
  writePvdSeries(dir + "/s.pvd", m);
  const mesh::UnstructuredMesh back = readMesh(dir + "/s.pvd");
  const mesh::UnstructuredMesh first = readMesh(dir + "/s/s_t0.pvtu");  // the geometry, welded
  EXPECT_EQ(back.points, first.points);
  for (int t = 0; t < mesh::kNumCellTypes; ++t) EXPECT_EQ(back.cells[t], first.cells[t]);
  EXPECT_EQ(back.timeValues, m.timeValues);
  ASSERT_EQ(back.fields.size(), 3u);
  for (const mesh::Field& f : back.fields) {
    ASSERT_EQ(f.numSteps(), 3u) << f.name;
    const mesh::Field& written = *m.findField(f.name);
    for (size_t k = 0; k < 3; ++k) {
      // The welded order: point i is the written mesh's point at the same position.
      const mesh::UnstructuredMesh alone = readMesh(dir + "/s/s_t" + std::to_string(k) + ".pvtu");
      EXPECT_EQ(f.steps[k], alone.findField(f.name)->steps[0]) << f.name << " step " << k;
      double sum = 0, want = 0;
      for (float v : f.steps[k]) sum += v;
      for (float v : stepOf(written, k)) want += v;
      EXPECT_NEAR(sum, want, 1e-3) << f.name << " step " << k;  // the values written, moved only
    }
  }
  EXPECT_EQ(formatDescription(dir + "/s.pvd"),
            "time series (ParaView .pvd) of 3 files, each a parallel VTK XML unstructured grid "
            "(.pvtu)");
  EXPECT_EQ(countPieces(dir + "/s.pvd"), 2);
  EXPECT_TRUE(readsByPiece(dir + "/s.pvd"));
  EXPECT_TRUE(readsStepsAlone(dir + "/s.pvd"));
  EXPECT_EQ(pieceCellCounts(dir + "/s.pvd"), pieceCellCounts(dir + "/s/s_t0.pvtu"));
  EXPECT_EQ(meshFiles(dir + "/s.pvd").size(), 1u + 3u * 3u);  // the index, 3 x (.pvtu + 2 pieces)
}

TEST(Series, OneStepPiecesAndStreamingAgreeWithTheWholeRead) {
  const std::string dir = sm::test::outputDir("Series.OneStep");
  writePvdSeries(dir + "/s.pvd", threeSteps());
  const mesh::UnstructuredMesh all = readMesh(dir + "/s.pvd");
  ReadOptions o;
  o.step = 2;
  const mesh::UnstructuredMesh two = readMesh(dir + "/s.pvd", o);
  EXPECT_EQ(two.timeValues, (std::vector<double>{0.0, 0.25, 1.5}));  // every step's, as .vtu
  for (const mesh::Field& f : two.fields) {
    ASSERT_EQ(f.numSteps(), 1u);
    EXPECT_EQ(f.steps[0], all.findField(f.name)->steps[2]) << f.name;
  }
  o.step = 7;  // beyond the last: the last, as ReadOptions::step promises
  EXPECT_EQ(readMesh(dir + "/s.pvd", o).findField("h")->steps[0], all.findField("h")->steps[2]);

  const std::vector<FieldStepCount> listed = listFieldSteps(dir + "/s.pvd");
  ASSERT_EQ(listed.size(), 3u);
  for (const FieldStepCount& f : listed) EXPECT_EQ(f.steps, 3u) << f.name;
  for (uint64_t k = 0; k < 3; ++k)
    EXPECT_EQ(readFieldStep(dir + "/s.pvd", "h", k, {}, all.pointOrigin),
              all.findField("h")->steps[k]);
  EXPECT_NE(fileErrorOf([&] {
              readFieldStep(dir + "/s.pvd", "h", 3);
            }).find("s.pvd: field 'h' has 3 time steps (0 .. 2), not step 3"),
            std::string::npos);

  // Piece 1 of every step, as a rank reads its share.
  ReadOptions piece;
  piece.pieces = {1};
  const mesh::UnstructuredMesh mine = readMesh(dir + "/s.pvd", piece);
  for (uint64_t k = 0; k < 3; ++k) {
    const mesh::UnstructuredMesh alone =
        readMesh(dir + "/s/s_t" + std::to_string(k) + ".pvtu", piece);
    EXPECT_EQ(mine.findField("h")->steps[k], alone.findField("h")->steps[0]);
    EXPECT_EQ(readFieldStep(dir + "/s.pvd", "h", k, piece, mine.pointOrigin),
              alone.findField("h")->steps[0]);
  }
}

TEST(Series, JsonSeriesIsSortedByTime) {
  const std::string dir = sm::test::outputDir("Series.Json");
  writePvdSeries(dir + "/s.pvd", threeSteps());
  // Listed out of order, with other times: the times decide the order.
  writeText(dir + "/s.vtu.series",
            R"({"file-series-version": "1.0", "files": [
                {"name": "s/s_t2.pvtu", "time": 9.5},
                {"name": "s/s_t0.pvtu", "time": -1},
                {"name": "s/s_t1.pvtu", "time": 3}]})");
  const mesh::UnstructuredMesh json = readMesh(dir + "/s.vtu.series");
  const mesh::UnstructuredMesh pvd = readMesh(dir + "/s.pvd");
  EXPECT_EQ(json.timeValues, (std::vector<double>{-1, 3, 9.5}));
  for (size_t k = 0; k < 3; ++k)
    EXPECT_EQ(json.findField("h")->steps[k], pvd.findField("h")->steps[k]);
}

TEST(Series, CellDataStepsAverageOntoPoints) {
  const std::string dir = sm::test::outputDir("Series.CellData");
  writeText(dir + "/a.vtu", twoTets(1, 3));
  writeText(dir + "/b.vtu", twoTets(2, 6));
  writeText(dir + "/c.pvd",
            "<VTKFile type=\"Collection\"><Collection>"
            "<DataSet timestep=\"0.5\" file=\"b.vtu\"/><DataSet timestep=\"0\" file=\"a.vtu\"/>"
            "</Collection></VTKFile>");
  ReadOptions o;
  o.fields = {"p"};
  EXPECT_TRUE(asksForCellData(dir + "/c.pvd", o));
  const mesh::UnstructuredMesh m = readMesh(dir + "/c.pvd", o);
  ASSERT_EQ(m.fields.size(), 1u);
  // Points 1, 2, 3 are used by both cells, point 0 by the first, point 4 by the second.
  EXPECT_EQ(m.fields[0].steps[0], (std::vector<float>{1, 2, 2, 2, 3}));
  EXPECT_EQ(m.fields[0].steps[1], (std::vector<float>{2, 4, 4, 4, 6}));
  EXPECT_EQ(m.timeValues, (std::vector<double>{0, 0.5}));
  o.cellDataOnPoints = false;  // left to the ranks: every step of the cells
  const mesh::UnstructuredMesh cells = readMesh(dir + "/c.pvd", o);
  ASSERT_EQ(cells.cellFields.size(), 1u);
  ASSERT_EQ(cells.cellFields[0].steps.size(), 2u);
  EXPECT_EQ(cells.cellFields[0].steps[1][0], (std::vector<float>{2, 6}));
}

// A header whose <Piece> tag starts `at` bytes into the file (ascii field data before it), then
// twoTets' piece: steps whose headers outgrow the first bytes a size check reads.
std::string paddedTwoTets(size_t at) {
  std::string text = twoTets(1, 3);
  const size_t piece = text.find("<Piece");
  std::string pad =
      "<FieldData><DataArray type=\"Float64\" Name=\"note\" NumberOfTuples=\"1\" "
      "format=\"ascii\">7";
  const std::string close = "</DataArray></FieldData>";
  pad += std::string(at - piece - pad.size() - close.size(), ' ') + close;
  text.insert(piece, pad);
  return text;
}

TEST(Series, LongHeadersAreSizedWhole) {
  const std::string dir = sm::test::outputDir("Series.LongHeaders");
  // The tag cut by the first 4 KiB read, then field data longer than 64 KiB.
  for (size_t at : {size_t(4096 - 20), size_t(4096 - 40), size_t(100000)}) {
    writeText(dir + "/a.vtu", paddedTwoTets(at));
    writeText(dir + "/b.vtu", paddedTwoTets(at + 13));  // cut elsewhere
    writeText(dir + "/c.pvd",
              "<VTKFile type=\"Collection\"><Collection><DataSet file=\"a.vtu\"/>"
              "<DataSet file=\"b.vtu\"/></Collection></VTKFile>");
    ReadOptions o;
    o.fields = {"p"};
    EXPECT_EQ(readMesh(dir + "/a.vtu", o).numCells(), 2u) << at;
    const mesh::UnstructuredMesh m = readMesh(dir + "/c.pvd", o);
    EXPECT_EQ(m.numCells(), 2u) << at;
    EXPECT_EQ(m.fields.at(0).numSteps(), 2u) << at;
    EXPECT_EQ(listFieldSteps(dir + "/c.pvd", o).at(0).steps, 2u) << at;
  }
}

TEST(Series, StepsReadWholeAndTimesByPosition) {
  const std::string dir = sm::test::outputDir("Series.Legacy");
  writeText(dir + "/a.vtk", legacyTwoTets(1));
  writeText(dir + "/b.vtk", legacyTwoTets(2));
  writeText(dir + "/c.vtk", legacyTwoTets(3));
  // A data set with no timestep counts as its position (here 1, between 0.5 and 1.5).
  writeText(dir + "/s.pvd",
            "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"1.5\" file=\"c.vtk\"/>"
            "<DataSet file=\"b.vtk\"/><DataSet timestep=\"0.5\" file=\"a.vtk\"/>"
            "</Collection></VTKFile>");
  const mesh::UnstructuredMesh m = readMesh(dir + "/s.pvd");
  EXPECT_EQ(m.timeValues, (std::vector<double>{0.5, 1, 1.5}));
  ASSERT_EQ(m.fields.size(), 1u);
  ASSERT_EQ(m.fields[0].numSteps(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(m.fields[0].steps[k][4], 4.0f * float(k + 1)) << k;
  EXPECT_FALSE(readsStepsAlone(dir + "/s.pvd"));
  EXPECT_EQ(readFieldStep(dir + "/s.pvd", "f", 2), m.fields[0].steps[2]);
  EXPECT_EQ(listFieldSteps(dir + "/s.pvd").at(0).steps, 3u);
  // Another mesh in a later step: compared by its counts after the whole read.
  writeText(dir + "/d.vtk",
            "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
            "0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n"
            "POINT_DATA 4\nSCALARS f float 1\nLOOKUP_TABLE default\n1 2 3 4\n");
  writeText(dir + "/t.pvd",
            "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"0\" file=\"a.vtk\"/>"
            "<DataSet timestep=\"1\" file=\"d.vtk\"/></Collection></VTKFile>");
  EXPECT_NE(fileErrorOf([&] {
              readMesh(dir + "/t.pvd");
            }).find("step 1 ('" + dir + "/d.vtk') has 4 points and 1 cells, step 0 5 and 2"),
            std::string::npos);
}

TEST(Series, BadIndexesAndStepsAreNamed) {
  const std::string dir = sm::test::outputDir("Series.Errors");
  writeText(dir + "/a.vtu", twoTets(1, 3));
  writeText(dir + "/b.vtu", twoTets(2, 6));
  auto expectError = [&](const std::string& name, const std::string& text,
                         const std::string& part) {
    writeText(dir + "/" + name, text);
    ReadOptions o;
    o.fields = {"p"};
    const std::string message = fileErrorOf([&] { readMesh(dir + "/" + name, o); });
    EXPECT_NE(message.find(part), std::string::npos) << name << ": " << message;
  };
  const std::string head = "<VTKFile type=\"Collection\"><Collection>";
  const std::string tail = "</Collection></VTKFile>";
  expectError("empty.pvd", head + tail, "empty.pvd: names no files");
  expectError("broken.pvd", head + "<DataSet file=\"a.vtu\">",
              "broken.pvd: is not well-formed XML");
  expectError("type.pvd", "<VTKFile type=\"UnstructuredGrid\"/>",
              "type.pvd: is not a ParaView data collection");
  expectError("nofile.pvd", head + "<DataSet timestep=\"0\"/>" + tail,
              "nofile.pvd: data set 0 has no file attribute");
  expectError("time.pvd", head + "<DataSet timestep=\"soon\" file=\"a.vtu\"/>" + tail,
              "time.pvd: data set 'a.vtu' has timestep \"soon\", not a number");
  expectError("hex.pvd", head + "<DataSet timestep=\"0x10\" file=\"a.vtu\"/>" + tail,
              "hex.pvd: data set 'a.vtu' has timestep \"0x10\", not a number");
  expectError("inf.pvd", head + "<DataSet timestep=\"inf\" file=\"a.vtu\"/>" + tail,
              "has time inf, not a finite number");
  expectError("parts.pvd",
              head +
                  "<DataSet timestep=\"0\" part=\"0\" file=\"a.vtu\"/>"
                  "<DataSet timestep=\"0\" part=\"1\" file=\"b.vtu\"/>" +
                  tail,
              "parts.pvd: time 0 has two files");
  expectError("nested.pvd", head + "<DataSet file=\"empty.pvd\"/>" + tail,
              "nested.pvd: names another series");
  expectError("mixed.pvd",
              head +
                  "<DataSet timestep=\"0\" file=\"a.vtu\"/><DataSet timestep=\"1\" "
                  "file=\"x.vtk\"/>" +
                  tail,
              "mixed.pvd: mixes formats");
  expectError("missing.pvd",
              head +
                  "<DataSet timestep=\"0\" file=\"a.vtu\"/><DataSet timestep=\"1\" "
                  "file=\"gone.vtu\"/>" +
                  tail,
              "gone.vtu");
  expectError("json.series", "{\"files\": 3}", "json.series: is not a file series");
  expectError("bad.series", "{\"files\": [", "bad.series: is not valid JSON");
  expectError("noname.series", "{\"files\": [{\"time\": 0}]}",
              "noname.series: entry 0 of \"files\" has no \"name\" string");

  // A later step on another mesh: by its header for .vtu and .pvtu, before any value is read.
  const std::string other = dir + "/other";
  writePvdSeries(other + "/big.pvd", test::makeTestMesh(3, 1));
  writePvdSeries(other + "/small.pvd", test::makeTestMesh(2, 1));
  writeText(other + "/grown.pvd", head +
                                      "<DataSet timestep=\"0\" file=\"small/small_t0.pvtu\"/>"
                                      "<DataSet timestep=\"1\" file=\"big/big_t1.pvtu\"/>" +
                                      tail);
  EXPECT_NE(fileErrorOf([&] {
              readMesh(other + "/grown.pvd");
            }).find("grown.pvd: step 1 ('" + other + "/big/big_t1.pvtu') has "),
            std::string::npos);
  EXPECT_NE(fileErrorOf([&] {
              readFieldStep(other + "/grown.pvd", "f", 1);
            }).find("every step of a series must be the same mesh"),
            std::string::npos);

  // A file of a series holding several steps of a field.
  writePvtu(other + "/steps.pvtu", test::makeTestMesh(2, 1));  // g has 2 steps
  writeText(other + "/steps.pvd", head + "<DataSet file=\"steps.pvtu\"/>" + tail);
  EXPECT_NE(fileErrorOf([&] {
              readMesh(other + "/steps.pvd");
            }).find("holds field 'g' with 2 time steps; in a series each file holds one step"),
            std::string::npos);

  const std::vector<uint8_t> bytes{'<'};
  EXPECT_THROW(readMeshFromMemory(bytes, "x.pvd"), Error);

  // Times a reader would put in another order are refused when written.
  mesh::UnstructuredMesh backwards = threeSteps();
  backwards.timeValues = {0.0, 2.0, 1.0};
  EXPECT_THROW(writePvdSeries(other + "/backwards.pvd", backwards), Error);
  EXPECT_FALSE(fs::exists(other + "/backwards.pvd"));
}

}  // namespace
}  // namespace sm::io
