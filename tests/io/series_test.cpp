// Time series written one file per step (.pvd, .series): read back as one mesh whose fields have a
// step per file in time order, with the steps' times; one step alone; the streaming calls; cell
// data; and every malformed index or step that does not fit named by file.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>

#include "io/file_bytes.h"
#include "io/mesh_io.h"
#include "io/vtu_arrays.h"
#include "io/vtu_document.h"
#include "io_test_util.h"
#include "support/test_support.h"

namespace sm::io {
namespace {

namespace fs = std::filesystem;
using test::fileErrorOf;
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

// Two tetrahedra sharing a face, cell array p, as an ascii .vtu.
std::string twoTets(float p0, float p1) {
  return "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\"><UnstructuredGrid>"
         "<Piece NumberOfPoints=\"5\" NumberOfCells=\"2\"><Points>"
         "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">"
         "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1</DataArray></Points><Cells>"
         "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 2 3 1 2 3 4"
         "</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">4 8</DataArray>"
         "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">10 10</DataArray></Cells>"
         "<CellData><DataArray type=\"Float32\" Name=\"p\" format=\"ascii\">" +
         std::to_string(p0) + " " + std::to_string(p1) +
         "</DataArray></CellData></Piece></UnstructuredGrid></VTKFile>";
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

// Two tetrahedra with point field f as a legacy ascii .vtk: a format read whole for every step.
// DIR/NAME, a .pvd of two steps: FIRST at time 0, SECOND at time 1.
std::string twoStepSeries(const std::string& dir, const std::string& name, const std::string& first,
                          const std::string& second) {
  writeText(dir + "/" + name,
            "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"0\" file=\"" + first +
                "\"/><DataSet timestep=\"1\" file=\"" + second + "\"/></Collection></VTKFile>");
  return dir + "/" + name;
}

std::string legacyTwoTets(float scale) {
  std::string f;
  for (int i = 0; i < 5; ++i) f += std::to_string(scale * float(i)) + " ";
  return "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n"
         "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1\nCELLS 2 10\n4 0 1 2 3\n4 1 2 3 4\nCELL_TYPES 2\n10\n10\n"
         "POINT_DATA 5\nSCALARS f float 1\nLOOKUP_TABLE default\n" +
         f + "\n";
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

TEST(Series, CellDataStepsWithPiecesInAnotherOrderAreRefused) {
  const std::string dir = sm::test::outputDir("Series.CellPieces");
  // Pieces of different sizes: a.vtu two tetrahedra, b.vtu one.
  writeText(dir + "/a.vtu", twoTets(1, 3));
  std::string one = twoTets(5, 0);
  auto edit = [&](const std::string& from, const std::string& to) {
    const size_t at = one.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    one.replace(at, from.size(), to);
  };
  edit("NumberOfCells=\"2\"", "NumberOfCells=\"1\"");
  edit(">0 1 2 3 1 2 3 4<", ">1 2 3 4<");
  edit(">4 8<", ">4<");
  edit(">10 10<", ">10<");
  edit(">5.000000 0.000000<", ">5.000000<");
  writeText(dir + "/b.vtu", one);
  writeText(dir + "/s0.pvtu",
            "<VTKFile type=\"PUnstructuredGrid\"><PUnstructuredGrid><Piece Source=\"a.vtu\"/>"
            "<Piece Source=\"b.vtu\"/></PUnstructuredGrid></VTKFile>");
  writeText(dir + "/s1.pvtu",
            "<VTKFile type=\"PUnstructuredGrid\"><PUnstructuredGrid><Piece Source=\"b.vtu\"/>"
            "<Piece Source=\"a.vtu\"/></PUnstructuredGrid></VTKFile>");
  writeText(dir + "/s.pvd",
            "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"0\" file=\"s0.pvtu\"/>"
            "<DataSet timestep=\"1\" file=\"s1.pvtu\"/></Collection></VTKFile>");
  ReadOptions o;
  o.fields = {"p"};
  EXPECT_EQ(readMesh(dir + "/s0.pvtu", o).numCells(), 3u);  // the pieces themselves are fine
  for (bool onPoints : {true, false}) {
    o.cellDataOnPoints = onPoints;
    EXPECT_NE(fileErrorOf([&] { readMesh(dir + "/s.pvd", o); })
                  .find("step 1 ('" + dir +
                        "/s1.pvtu') piece 0 has 5 points and 1 cells, that "
                        "of step 0 5 and 2"),
              std::string::npos);
  }
}

// A later step holding the field with another number of components (a vector where step 0 has a
// scalar) is refused when the series is listed, as within one file, point and cell data alike:
// read, its magnitude would have been drawn with step 0's range. Before, it was accepted.
TEST(Series, AStepWithAnotherNumberOfComponentsIsRefused) {
  const std::string dir = sm::test::outputDir("Series.Components");
  auto withComponents = [](int n, bool cellData) {
    std::string x = twoTets(1, 3);
    const std::string from = "<CellData><DataArray type=\"Float32\" Name=\"p\" format=\"ascii\">";
    std::string values;
    for (int i = 0; i < (cellData ? 2 : 5) * n; ++i) values += std::to_string(i % 7) + " ";
    const std::string array = "<DataArray type=\"Float32\" Name=\"p\" NumberOfComponents=\"" +
                              std::to_string(n) + "\" format=\"ascii\">" + values + "</DataArray>";
    const size_t at = x.find(from);
    x.replace(
        at, x.find("</CellData>") - at + 11,
        cellData ? "<CellData>" + array + "</CellData>" : "<PointData>" + array + "</PointData>");
    return x;
  };
  // A series of two steps, the files named.
  auto series = [&](const std::string& name, const std::string& first, const std::string& second) {
    writeText(dir + "/" + name,
              "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"0\" file=\"" + first +
                  "\"/><DataSet timestep=\"1\" file=\"" + second + "\"/></Collection></VTKFile>");
    return dir + "/" + name;
  };
  auto asking = [](const std::string& field) {
    ReadOptions o;
    o.fields = {field};
    return o;
  };
  for (bool cellData : {false, true}) {
    const std::string kind = cellData ? "c" : "p";
    writeText(dir + "/" + kind + "1.vtu", withComponents(1, cellData));
    writeText(dir + "/" + kind + "3.vtu", withComponents(3, cellData));
    const std::string grown = series(kind + ".pvd", kind + "1.vtu", kind + "3.vtu");
    const std::string want =
        "step 1 ('" + dir + "/" + kind + "3.vtu') holds 'p' with 3 components, step 0 with 1";
    EXPECT_NE(fileErrorOf([&] { listFieldSteps(grown, asking("p")); }).find(want),
              std::string::npos)
        << kind;
    EXPECT_NE(fileErrorOf([&] { readMesh(grown, asking("p")); }).find(want), std::string::npos)
        << kind;
    // The same number of components in every step reads (the magnitude, both steps).
    const mesh::UnstructuredMesh m =
        readMesh(series(kind + "-same.pvd", kind + "3.vtu", kind + "3.vtu"), asking("p"));
    ASSERT_EQ(m.fields.size(), 1u) << kind;
    EXPECT_EQ(m.fields[0].numSteps(), 2u) << kind;
  }
  // One component of a point array reads from steps with 3 and 4 components alike; the array
  // whole does not, and a component past a step's is named by that step.
  writeText(dir + "/p4.vtu", withComponents(4, false));
  const std::string p34 = series("p34.pvd", "p3.vtu", "p4.vtu");
  const mesh::UnstructuredMesh m = readMesh(p34, asking("p[1]"));
  ASSERT_EQ(m.fields.size(), 1u);
  EXPECT_EQ(m.fields[0].numSteps(), 2u);
  EXPECT_NE(fileErrorOf([&] {
              listFieldSteps(p34, asking("p"));
            }).find("holds 'p' with 4 components, step 0 with 3"),
            std::string::npos);
  EXPECT_NE(fileErrorOf([&] {
              listFieldSteps(series("p43.pvd", "p4.vtu", "p3.vtu"), asking("p[3]"));
            }).find("p3.vtu: field 'p[3]': point array 'p' has 3 components"),
            std::string::npos);
}

// A later step whose points moved (a moving or deforming mesh, or one renumbered with the same
// counts) would draw its values at step 0's positions: refused, naming the step and the point,
// whether the series is read whole or a step at a time, in every format.
TEST(Series, AStepWhosePointsMovedIsRefused) {
  const std::string dir = sm::test::outputDir("Series.Moved");
  auto series = [&](const std::string& name, const std::string& first, const std::string& second) {
    return twoStepSeries(dir, name, first, second);
  };
  ReadOptions p;
  p.fields = {"p"};
  // .vtu steps: the apex (point 4) moves from (1, 1, 1) to (3, 1, 1).
  std::string moved = twoTets(1, 3);
  moved.replace(moved.find("0 0 1 1 1 1"), 11, "0 0 1 3 1 1");
  writeText(dir + "/a.vtu", twoTets(1, 3));
  writeText(dir + "/b.vtu", moved);
  const std::string vtu = series("vtu.pvd", "a.vtu", "b.vtu");
  const std::string want = "vtu.pvd: step 1 ('" + dir +
                           "/b.vtu') has point 4 at (3, 1, 1), step 0 at (1, 1, 1): every "
                           "step of a series must be the same mesh";
  EXPECT_NE(fileErrorOf([&] { readMesh(vtu, p); }).find(want), std::string::npos);
  EXPECT_NE(fileErrorOf([&] { readCellFieldStep(vtu, "p", 1); }).find(want), std::string::npos);
  EXPECT_EQ(readCellFieldStep(vtu, "p", 0), (std::vector<float>{1, 3}));  // step 0 is itself
  // The same points written another way (-0 for 0, 1.0 for 1, other spacing) are the same mesh.
  std::string same = twoTets(2, 4);
  same.replace(same.find("0 0 0 1 0 0"), 11, "-0 0 0  1.0 0 0");
  writeText(dir + "/c.vtu", same);
  const mesh::UnstructuredMesh ok = readMesh(series("same.pvd", "a.vtu", "c.vtu"), p);
  EXPECT_EQ(ok.fields.at(0).numSteps(), 2u);
  EXPECT_EQ(readCellFieldStep(dir + "/same.pvd", "p", 1), (std::vector<float>{2, 4}));

  // .pvtu steps: the point is named by its piece; a rank reading the other piece alone reads on.
  mesh::UnstructuredMesh mesh = test::makeTestMesh(3, 2);
  std::erase_if(mesh.fields, [](const mesh::Field& f) { return f.numSteps() > 1; });  // one each
  writePvtu(dir + "/m0.pvtu", mesh);
  const std::vector<std::string> pieces = pieceFiles(dir + "/m0.pvtu");
  const mesh::UnstructuredMesh piece1 = readMesh(pieces.at(1));
  const glm::dvec3 last = piece1.points.back();
  for (glm::dvec3& q : mesh.points)
    if (q == last) q.z += 0.5;
  writePvtu(dir + "/m1.pvtu", mesh);
  const std::string pvtu = series("pvtu.pvd", "m0.pvtu", "m1.pvtu");
  const std::string piece = "of piece '" + dir + "/m1/m1_1.vtu'";
  EXPECT_NE(fileErrorOf([&] { readMesh(pvtu); }).find(piece), std::string::npos);
  EXPECT_NE(fileErrorOf([&] { readFieldStep(pvtu, "f", 1); }).find(piece), std::string::npos);
  ReadOptions first;
  first.pieces = {0};
  if (readMesh(pieces.at(0)).points != readMesh(dir + "/m1/m1_0.vtu").points) {
    ADD_FAILURE() << "the moved point is also in piece 0: the test needs another point";
  } else {
    EXPECT_EQ(readMesh(pvtu, first).fields.at(0).numSteps(), 2u);
    EXPECT_NO_THROW(readFieldStep(pvtu, "f", 1, first));
  }

  // Legacy .vtk steps, read whole: compared in memory, streamed or not.
  std::string legacy = legacyTwoTets(1);
  writeText(dir + "/a.vtk", legacy);
  legacy.replace(legacy.find("0 0 1 1 1 1"), 11, "0 0 1 1 1 2");
  writeText(dir + "/b.vtk", legacy);
  const std::string vtk = series("vtk.pvd", "a.vtk", "b.vtk");
  const std::string vtkWant = "step 1 ('" + dir + "/b.vtk') has point 4 at (1, 1, 2)";
  EXPECT_NE(fileErrorOf([&] { readMesh(vtk); }).find(vtkWant), std::string::npos);
  EXPECT_NE(fileErrorOf([&] { readFieldStep(vtk, "f", 1); }).find(vtkWant), std::string::npos);
}

TEST(Series, AStepWhoseCellsChangedIsRefused) {
  const std::string dir = sm::test::outputDir("Series.Remeshed");
  auto series = [&](const std::string& name, const std::string& first, const std::string& second) {
    return twoStepSeries(dir, name, first, second);
  };
  auto edited = [](std::string text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? text : text.replace(at, from.size(), to);
  };
  auto refused = [](const std::function<void()>& f, const std::string& part) {
    const std::string message = fileErrorOf(f);
    EXPECT_NE(message.find(part), std::string::npos) << message;
    EXPECT_NE(message.find("every step of a series must be the same mesh, its cells joining the "
                           "same points in the same order"),
              std::string::npos)
        << message;
  };
  ReadOptions p;
  p.fields = {"p"};
  // .vtu steps, points unchanged: the second tetrahedron's vertices turned (an even permutation,
  // still a valid cell), the two cells swapped (a renumbering), a cell of another type.
  const std::string cells = "0 1 2 3 1 2 3 4";
  writeText(dir + "/a.vtu", twoTets(1, 3));
  writeText(dir + "/turned.vtu", edited(twoTets(1, 3), cells, "0 1 2 3 2 3 1 4"));
  writeText(dir + "/swapped.vtu", edited(twoTets(3, 1), cells, "1 2 3 4 0 1 2 3"));
  writeText(dir + "/typed.vtu", edited(twoTets(1, 3), "10 10", "10 14"));
  const std::string turned = series("turned.pvd", "a.vtu", "turned.vtu");
  const std::string want = "turned.pvd: step 1 ('" + dir +
                           "/turned.vtu') has cell 1 (tetrahedron: points 2 3 1 4), step 0 "
                           "(tetrahedron: points 1 2 3 4): ";
  refused([&] { readMesh(turned, p); }, want);
  refused([&] { readCellFieldStep(turned, "p", 1); }, want);
  EXPECT_EQ(readCellFieldStep(turned, "p", 0), (std::vector<float>{1, 3}));  // step 0 is itself
  refused([&] { readMesh(series("swapped.pvd", "a.vtu", "swapped.vtu"), p); },
          "has cell 0 (tetrahedron: points 1 2 3 4), step 0 (tetrahedron: points 0 1 2 3)");
  refused([&] { readMesh(series("typed.pvd", "a.vtu", "typed.vtu"), p); },
          "has cell 1 (pyramid: points 1 2 3 4), step 0 (tetrahedron: points 1 2 3 4)");
  // The same cells written another way (another integer type, other spacing) are the same mesh.
  std::string same =
      edited(twoTets(2, 4), "Int64\" Name=\"connectivity", "Int32\" Name=\"connectivity");
  writeText(dir + "/same.vtu", edited(same, cells, " 0 1 2 3\n1  2 3 4 "));
  EXPECT_EQ(readMesh(series("same.pvd", "a.vtu", "same.vtu"), p).fields.at(0).numSteps(), 2u);
  EXPECT_EQ(readCellFieldStep(dir + "/same.pvd", "p", 1), (std::vector<float>{2, 4}));

  // .pvtu steps: a hexahedron of the last cluster turned about its axis (the same points); the
  // cell is named by its piece, and a rank reading another piece alone reads on.
  mesh::UnstructuredMesh mesh = test::makeTestMesh(3, 2);
  std::erase_if(mesh.fields, [](const mesh::Field& f) { return f.numSteps() > 1; });  // one each
  writePvtu(dir + "/m0.pvtu", mesh);
  const size_t hex = mesh::typeIndex(mesh::CellType::Hex);
  const auto last = std::find(mesh.clusters[hex].rbegin(), mesh.clusters[hex].rend(), 1);
  ASSERT_NE(last, mesh.clusters[hex].rend()) << "the test mesh has a hexahedron in cluster 1";
  uint32_t* h = mesh.cells[hex].data() + 8 * (mesh.clusters[hex].rend() - last - 1);
  std::rotate(h, h + 1, h + 4);
  std::rotate(h + 4, h + 5, h + 8);
  writePvtu(dir + "/m1.pvtu", mesh);
  const std::string pvtu = series("pvtu.pvd", "m0.pvtu", "m1.pvtu");
  const std::string piece = "of piece '" + dir + "/m1/m1_1.vtu' (hexahedron: points ";
  refused([&] { readMesh(pvtu); }, piece);
  refused([&] { readFieldStep(pvtu, "f", 1); }, piece);
  ReadOptions first;
  first.pieces = {0};
  EXPECT_EQ(readMesh(pvtu, first).fields.at(0).numSteps(), 2u);
  EXPECT_NO_THROW(readFieldStep(pvtu, "f", 1, first));

  // Legacy .vtk steps, read whole: compared in memory, streamed or not; named by type.
  writeText(dir + "/a.vtk", legacyTwoTets(1));
  writeText(dir + "/b.vtk", edited(legacyTwoTets(1), "4 1 2 3 4", "4 2 3 1 4"));
  const std::string vtk = series("vtk.pvd", "a.vtk", "b.vtk");
  const std::string vtkWant = "step 1 ('" + dir +
                              "/b.vtk') has tetrahedron 1 (tetrahedron: points 2 3 1 4), step 0 "
                              "(tetrahedron: points 1 2 3 4)";
  refused([&] { readMesh(vtk); }, vtkWant);
  refused([&] { readFieldStep(vtk, "f", 1); }, vtkWant);
}

// A series' steps are first compared by how their mesh arrays are stored: the digest must follow
// the arrays' bytes wherever they sit in the appended data, and tell different bytes apart.
TEST(Series, StoredMeshArraysAreComparedByTheirBytesWhereverTheySit) {
  const std::string dir = sm::test::outputDir("Series.Encoded");
  mesh::UnstructuredMesh m = test::makeTestMesh(3, 1);
  writeVtu(dir + "/a.vtu", m);
  std::reverse(m.fields.begin(), m.fields.end());  // other arrays' sizes before and after
  m.fields.pop_back();
  writeVtu(dir + "/b.vtu", m);
  m.points.back().x += 0.25;
  writeVtu(dir + "/c.vtu", m);
  struct Stored {
    FileBytes bytes;
    VtuDocument doc;
    VtuPiece piece;
    explicit Stored(const std::string& f)
        : bytes(FileBytes::openLazily(f)),
          doc(bytes, f, "UnstructuredGrid"),
          piece(vtuPieces(doc).at(0)) {}
    uint64_t points() const {
      return doc.encodedDigest(piece.node.child("Points").child("DataArray"));
    }
    uint64_t cells(const char* name) const {
      return doc.encodedDigest(findDataArray(piece.node.child("Cells"), name));
    }
  };
  const Stored a(dir + "/a.vtu"), b(dir + "/b.vtu"), c(dir + "/c.vtu");
  ASSERT_NE(a.points(), 0u);
  EXPECT_NE(
      findDataArray(a.piece.node.child("Cells"), "connectivity").attribute("offset").as_ullong(),
      findDataArray(b.piece.node.child("Cells"), "connectivity").attribute("offset").as_ullong())
      << "the arrays should sit elsewhere in b";
  EXPECT_EQ(a.points(), b.points());
  for (const char* name : {"connectivity", "offsets", "types"})
    EXPECT_EQ(a.cells(name), b.cells(name)) << name;
  EXPECT_NE(a.cells("connectivity"), a.cells("offsets"));
  EXPECT_NE(b.points(), c.points());
  EXPECT_EQ(b.cells("connectivity"), c.cells("connectivity"));
  // A series of the three: a and b are one mesh (read on), c's moved point is found.
  writeText(dir + "/s.pvd",
            "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"0\" "
            "file=\"a.vtu\"/><DataSet timestep=\"1\" file=\"b.vtu\"/><DataSet "
            "timestep=\"2\" file=\"c.vtu\"/></Collection></VTKFile>");
  const std::string field = m.fields.front().name;
  EXPECT_NO_THROW(readFieldStep(dir + "/s.pvd", field, 1));
  EXPECT_NE(
      fileErrorOf([&] { readFieldStep(dir + "/s.pvd", field, 2); }).find("/c.vtu') has point "),
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
