// Polyhedron cells (VTK type 42) in every layout that describes their faces: .vtu up to VTK 9.3
// (faces, faceoffsets), .vtu from VTK 9.4 (face_connectivity, face_offsets, polyhedron_to_faces,
// polyhedron_offsets), legacy .vtk 4.2 (the face stream after the cell's count) and 5.1 (the face
// stream as the cell's connectivity). Files as python3-vtk9 9.1 writes them (the first and the
// legacy ones) or as the VTK 9.4 format description gives them.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "io/mesh_io.h"
#include "io_test_util.h"
#include "mesh/element_geometry.h"
#include "support/test_support.h"

namespace sm::io {
namespace {

using mesh::CellType;

// The unit cube as a polyhedron (cell 0) and the tetrahedron (0,0,0) (1,0,0) (1,1,0) (0,0,1)
// (cell 1), point field s = 0..7, cell array c = (10, 20).
const char* kCubeFaces = "6 4 0 3 2 1 4 4 5 6 7 4 0 1 5 4 4 1 2 6 5 4 2 3 7 6 4 3 0 4 7";
const char* kPoints = "0 0 0 1 0 0 1 1 0 0 1 0 0 0 1 1 0 1 1 1 1 0 1 1";

std::string vtuWith(const std::string& polyArrays, const std::string& points = kPoints,
                    int numPoints = 8) {
  return std::string("<VTKFile type=\"UnstructuredGrid\" version=\"0.1\"><UnstructuredGrid>") +
         "<Piece NumberOfPoints=\"" + std::to_string(numPoints) +
         "\" NumberOfCells=\"2\"><PointData><DataArray type=\"Float32\" Name=\"s\" "
         "format=\"ascii\">0 1 2 3 4 5 6 7</DataArray></PointData><CellData><DataArray "
         "type=\"Float32\" Name=\"c\" format=\"ascii\">10 20</DataArray></CellData><Points>"
         "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">" +
         points +
         "</DataArray></Points><Cells><DataArray type=\"Int64\" Name=\"connectivity\" "
         "format=\"ascii\">0 1 2 3 4 5 6 7 0 1 2 4</DataArray><DataArray type=\"Int64\" "
         "Name=\"offsets\" format=\"ascii\">8 12</DataArray><DataArray type=\"UInt8\" "
         "Name=\"types\" format=\"ascii\">42 10</DataArray>" +
         polyArrays + "</Cells></Piece></UnstructuredGrid></VTKFile>";
}

std::string streamArrays(const std::string& faces = kCubeFaces, const std::string& ends = "31 -1") {
  return "<DataArray type=\"Int64\" Name=\"faces\" format=\"ascii\">" + faces +
         "</DataArray><DataArray type=\"Int64\" Name=\"faceoffsets\" format=\"ascii\">" + ends +
         "</DataArray>";
}

// `extraFace`: one more face, listed by no polyhedron, at the end of the face arrays.
std::string faceArrays(const std::string& cellEnds = "6 6", bool extraFace = false) {
  auto a = [](const char* name, const std::string& v) {
    return std::string("<DataArray type=\"Int64\" Name=\"") + name + "\" format=\"ascii\">" + v +
           "</DataArray>";
  };
  return a("face_connectivity", std::string("0 3 2 1 4 5 6 7 0 1 5 4 1 2 6 5 2 3 7 6 3 0 4 7") +
                                    (extraFace ? " 0 1 2" : "")) +
         a("face_offsets", std::string("4 8 12 16 20 24") + (extraFace ? " 27" : "")) +
         a("polyhedron_to_faces", "0 1 2 3 4 5") + a("polyhedron_offsets", cellEnds);
}

std::string legacy42() {
  return std::string(
             "# vtk DataFile Version 4.2\nvtk output\nASCII\nDATASET UNSTRUCTURED_GRID\n"
             "POINTS 8 float\n") +
         kPoints + "\nCELLS 2 37\n31 " + kCubeFaces +
         "\n4 0 1 2 4\nCELL_TYPES 2\n42\n10\nPOINT_DATA 8\nSCALARS s float 1\nLOOKUP_TABLE "
         "default\n0 1 2 3 4 5 6 7\n";
}

std::string legacy51(const std::string& faces = kCubeFaces,
                     const std::string& offsets = "0 31 35") {
  const std::string ids = offsets.substr(offsets.rfind(' ') + 1);  // the connectivity's length
  return std::string(
             "# vtk DataFile Version 5.1\nvtk output\nASCII\nDATASET UNSTRUCTURED_GRID\n"
             "POINTS 8 float\n") +
         kPoints + "\nCELLS 3 " + ids + "\nOFFSETS vtktypeint64\n" + offsets +
         "\nCONNECTIVITY vtktypeint64\n" + faces +
         " 0 1 2 4\nCELL_TYPES 2\n42\n10\nPOINT_DATA 8\nSCALARS s float 1\nLOOKUP_TABLE "
         "default\n0 1 2 3 4 5 6 7\n";
}

std::string write(const std::string& name, const std::string& text) {
  const std::string dir = sm::test::outputDir("Polyhedra");
  test::writeText(dir + "/" + name, text);
  return dir + "/" + name;
}

double totalVolume(const mesh::UnstructuredMesh& m) {
  double v = 0;
  for (uint64_t i = 0; i < m.numCells(CellType::Tet); ++i)
    v += mesh::signedVolume(CellType::Tet, test::cellIds(m, CellType::Tet, i), m.points);
  return v;
}

void expectCubeAndTet(const mesh::UnstructuredMesh& m) {
  EXPECT_EQ(m.numCells(), 7u);
  EXPECT_EQ(m.numCells(CellType::Tet), 7u);
  EXPECT_EQ(m.skipped.polyhedraSplit, 1u);
  EXPECT_EQ(m.skipped.polyhedronTets, 6u);
  EXPECT_EQ(m.skipped.totalSkipped(), 0u);
  EXPECT_EQ(m.invertedFixed, 0u);
  test::expectAllPositive(m);
  EXPECT_NEAR(totalVolume(m), 1.0 + 1.0 / 6.0, 1e-6);
}

TEST(Polyhedra, EveryLayoutGivesTheSameTetrahedra) {
  const std::vector<std::pair<std::string, std::string>> files = {
      {"stream.vtu", vtuWith(streamArrays())},
      {"arrays.vtu", vtuWith(faceArrays())},
      {"arrays_unused_face.vtu", vtuWith(faceArrays("6 6", true))},
      {"v42.vtk", legacy42()},
      {"v51.vtk", legacy51()}};
  std::vector<std::vector<double>> first;
  for (const auto& [name, text] : files) {
    SCOPED_TRACE(name);
    const mesh::UnstructuredMesh m = readMesh(write(name, text));
    expectCubeAndTet(m);
    if (first.empty()) first = test::canonicalCells(m);
    EXPECT_EQ(test::canonicalCells(m), first);
  }
}

// Files VTK 9.1 wrote (tests/io/data/make_polyhedra.py): two cubes sharing a face and a hexagonal
// prism, in a zlib-compressed appended .vtu and binary legacy files of both layouts.
TEST(Polyhedra, FilesVtkWrote) {
  std::vector<std::vector<double>> first;
  for (const char* name :
       {"polyhedra.vtu", "polyhedra_v42_binary.vtk", "polyhedra_v51_binary.vtk"}) {
    SCOPED_TRACE(name);
    ReadOptions o;
    o.fields = {"s", "q"};
    const mesh::UnstructuredMesh m = readMesh(test::fixturePath(name), o);
    EXPECT_EQ(m.skipped.polyhedraSplit, 3u);
    EXPECT_EQ(m.numCells(), m.skipped.polyhedronTets);
    test::expectAllPositive(m);
    EXPECT_NEAR(totalVolume(m), 2.0 + 3.0 * std::sqrt(3.0) / 2.0, 1e-5);
    if (first.empty()) first = test::canonicalCells(m);
    EXPECT_EQ(test::canonicalCells(m), first);
    // Cell data q = 1, 2, 3 on the points: each polyhedron counts once at a point, as in
    // ParaView's Cell Data to Point Data, however many of its tetrahedra meet there (the face
    // x = 1 is on both cubes: 1.5; counted per tetrahedron it would lean to one side).
    const mesh::Field* q = m.findField("q");
    ASSERT_NE(q, nullptr);
    for (size_t p = 0; p < m.numPoints(); ++p) {
      const glm::dvec3 x = m.points[p];
      const float want = x.x > 2.5 ? 3.0f : x.x == 1.0 ? 1.5f : x.x < 1.0 ? 1.0f : 2.0f;
      EXPECT_EQ(q->steps[0][p], want) << x.x << " " << x.y << " " << x.z;
    }
  }
}

// Cell data follows the polyhedron into each of its tetrahedra, read with the mesh and read alone
// for a later step (cell origins).
TEST(Polyhedra, CellDataReachesEveryTetrahedronOfTheCell) {
  const std::string path = write("cells.vtu", vtuWith(streamArrays()));
  ReadOptions o;
  o.fields = {"c"};
  o.cellOrigins = true;
  o.cellDataOnPoints = false;
  const mesh::UnstructuredMesh m = readMesh(path, o);
  ASSERT_EQ(m.cellFields.size(), 1u);
  const std::vector<float>& c = m.cellFields[0].steps[0][mesh::typeIndex(CellType::Tet)];
  ASSERT_EQ(c.size(), 7u);
  EXPECT_EQ(std::count(c.begin(), c.end(), 10.0f), 6);
  EXPECT_EQ(std::count(c.begin(), c.end(), 20.0f), 1);
  EXPECT_EQ(readCellFieldStep(path, "c", 0, o, m.cellOrigin), c);
}

// A non-finite value on a polyhedron is one cell's, however many tetrahedra it became: the warning
// counts cells of the file.
TEST(Polyhedra, NonFiniteCellDataCountsTheCellOnce) {
  std::string text = vtuWith(streamArrays());
  const size_t at = text.find(">10 20<");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 7, ">nan 20<");
  const std::string path = write("nan.vtu", text);
  ReadOptions o;
  o.fields = {"c"};
  testing::internal::CaptureStderr();
  const mesh::UnstructuredMesh m = readMesh(path, o);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("cell data 'c' has 1 non-finite values"), std::string::npos) << err;
}

// Two <Piece>s in one file, the polyhedron in the second: its face ids are the piece's own.
TEST(Polyhedra, FaceIdsArePieceLocal) {
  std::string one = vtuWith(streamArrays());
  const std::string piece =
      one.substr(one.find("<Piece"), one.find("</Piece>") + 8 - one.find("<Piece"));
  std::string two = one;
  two.insert(two.find("</UnstructuredGrid>"), piece);
  // Move the second piece by 5 along x, so that a face that took the first piece's points shows.
  const size_t second = two.rfind(kPoints);
  two.replace(second, std::string(kPoints).size(),
              "5 0 0 6 0 0 6 1 0 5 1 0 5 0 1 6 0 1 6 1 1 5 1 1");
  const mesh::UnstructuredMesh m = readMesh(write("pieces.vtu", two));
  EXPECT_EQ(m.numCells(CellType::Tet), 14u);
  EXPECT_EQ(m.skipped.polyhedraSplit, 2u);
  test::expectAllPositive(m);
  EXPECT_NEAR(totalVolume(m), 2.0 * (1.0 + 1.0 / 6.0), 1e-6);
}

// One line naming the file and the cell for every kind of damage to a face description.
TEST(Polyhedra, DamagedFacesAreOneLineErrors) {
  struct Case {
    const char* name;
    std::string text, message;
  };
  const std::vector<Case> cases = {
      {"short.vtu", vtuWith(streamArrays("6 4 0 3 2 1 4 4 5 6 7", "11 -1")),
       "cell 0 (polyhedron): its face stream ends before face 2"},
      {"claims.vtu", vtuWith(streamArrays("99 4 0 3 2 1", "6 -1")),
       "cell 0 (polyhedron): its face stream claims 99 faces in 6 values"},
      {"runs_on.vtu", vtuWith(streamArrays(std::string(kCubeFaces) + " 7", "32 -1")),
       "its face stream has 1 values after its last face"},
      {"range.vtu",
       vtuWith(streamArrays("6 4 0 3 2 9 4 4 5 6 7 4 0 1 5 4 4 1 2 6 5 4 2 3 7 6 4 3 0 4 7")),
       "cell 0 (polyhedron): refers to point 9 but the file has 8 points"},
      {"two_points.vtu",
       vtuWith(streamArrays("6 2 0 3 4 4 5 6 7 4 0 1 5 4 4 1 2 6 5 4 2 3 7 6 4 3 0 4 7", "29 -1")),
       "face 0 has 2 points"},
      {"twice.vtu",
       vtuWith(streamArrays("6 4 0 3 3 1 4 4 5 6 7 4 0 1 5 4 4 1 2 6 5 4 2 3 7 6 4 3 0 4 7")),
       "face 0 uses point 3 twice"},
      {"ends.vtu",
       vtuWith("<DataArray type=\"Int64\" Name=\"faces\" format=\"ascii\">1</DataArray>"),
       "has polyhedra with a 'faces' array but no 'faceoffsets' array"},
      {"offsets.vtu", vtuWith(faceArrays("6 5")), "polyhedron_offsets: entry 1 (5) is smaller"},
      {"other_cell.vtu", vtuWith(streamArrays(kCubeFaces, "31 31")),
       "faceoffsets: cell 1 (VTK type 10) has the entry 31, but only polyhedra (type 42) have "
       "faces: -1 expected"},
      {"no_faces.vtu", vtuWith(faceArrays("0 6")),
       "polyhedron_offsets: polyhedron cell 0 has no faces"},
      {"no_to_faces.vtu",
       vtuWith("<DataArray type=\"Int64\" Name=\"polyhedron_offsets\" format=\"ascii\">6 "
               "6</DataArray>"),
       "has polyhedra but no 'polyhedron_to_faces' array"},
      {"v51.vtk",
       legacy51("6 4 0 3 2 1 4 4 5 6 7 4 0 1 5 4 4 1 2 6 5 4 2 3 7 6 4 3 0 4", "0 30 34"),
       "cell 0 (polyhedron): face 5 claims 4 points, past the end of its stream"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = write(c.name, c.text);
    const std::string e = test::fileErrorOf([&] { readMesh(path); });
    EXPECT_NE(e.find(path), std::string::npos) << e;
    EXPECT_NE(e.find(c.message), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
}

// A polyhedron that cannot be split on its own vertices, and one given without faces, are skipped
// and counted, with a warning that says which and why.
TEST(Polyhedra, UnsplittableCellsAreSkippedWithTheReason) {
  // The cube with its last face turned inside out.
  const std::string open =
      write("flipped.vtu",
            vtuWith(streamArrays("6 4 0 3 2 1 4 4 5 6 7 4 0 1 5 4 4 1 2 6 5 4 2 3 7 6 4 7 4 0 3")));
  testing::internal::CaptureStderr();
  mesh::UnstructuredMesh m = readMesh(open);
  std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(m.numCells(), 1u);
  EXPECT_EQ(m.skipped.polyhedra, 1u);
  EXPECT_EQ(m.skipped.polyhedraSplit, 0u);
  EXPECT_NE(
      err.find("skipped 1 polyhedron cells that cannot be split into tetrahedra on their own "
               "vertices (first: cell 0: its faces do not close, or do not all turn the same way)"),
      std::string::npos)
      << err;

  testing::internal::CaptureStderr();
  m = readMesh(write("nofaces.vtu", vtuWith("")));
  err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(m.numCells(), 1u);
  EXPECT_EQ(m.skipped.polyhedra, 1u);
  EXPECT_NE(err.find("skipped 1 polyhedron cells (the file gives no faces)"), std::string::npos)
      << err;
}

}  // namespace
}  // namespace sm::io
