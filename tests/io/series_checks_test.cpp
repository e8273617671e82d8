// Series whose steps are not the same mesh, or not the same data, are refused naming the step
// and what differs (io/series_same_mesh.cpp); the reading itself is in series_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <string>

#include "io/mesh_io.h"
#include "io/vtu_arrays.h"
#include "io/vtu_document.h"
#include "io_core/file_bytes.h"
#include "io_test_util.h"
#include "support/test_support.h"

namespace sm::io {
namespace {

using test::fileErrorOf;
using test::legacyTwoTets;
using test::twoStepSeries;
using test::twoTets;
using test::writeText;

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

}  // namespace
}  // namespace sm::io
