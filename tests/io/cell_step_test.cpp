// One step of cell data read on its own (io::readCellFieldStep with the cell origins a read kept,
// ReadOptions::cellOrigins): the same values, element for element, as readMesh's cell fields, for
// every .vtu encoding, for several <Piece>s in one file, for some of a .pvtu's pieces with skipped
// and ghost cells among them, and for a series; errors name the file and the array.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "io/mesh_io.h"
#include "io_test_util.h"
#include "support/test_support.h"

namespace sm::io {
namespace {

namespace fs = std::filesystem;
using test::fileErrorOf;
using test::writeText;

// A cell field's step, type after type (the order of cellOrigin).
std::vector<float> flatStep(const mesh::CellField& f, size_t step) {
  std::vector<float> v;
  for (const std::vector<float>& perType : f.steps.at(step))
    v.insert(v.end(), perType.begin(), perType.end());
  return v;
}

void expectSameBits(const std::vector<float>& a, const std::vector<float>& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
}

ReadOptions cellsKept(const std::string& field) {
  ReadOptions o;
  o.fields = {field};
  o.cellDataOnPoints = false;
  o.cellOrigins = true;
  return o;
}

TEST(CellStep, EveryVtuEncodingGivesReadMeshValues) {
  int files = 0;
  for (const auto& entry : fs::directory_iterator(test::fixturePath(""))) {
    const std::string path = entry.path().string();
    // Every encoding of the fixture mesh (mesh_int_types.vtu holds other arrays; polyhedra.vtu is
    // another mesh, polyhedra_test.cpp).
    if (entry.path().extension() != ".vtu" ||
        entry.path().filename().string().rfind("mesh_", 0) != 0 ||
        path.find("int_types") != std::string::npos)
      continue;
    SCOPED_TRACE(path);
    ++files;
    const ReadOptions o = cellsKept("quality");
    const mesh::UnstructuredMesh m = readMesh(path, o);
    ASSERT_EQ(m.cellFields.size(), 1u);
    ASSERT_EQ(m.cellOrigin.size(), m.numCells());
    EXPECT_EQ(m.fileCells, m.numCells() + 2);  // the triangle and the vertex are skipped
    expectSameBits(readCellFieldStep(path, "quality", 0, o, m.cellOrigin),
                   flatStep(m.cellFields[0], 0));
    // Without a map: one value per file cell, skipped cells included.
    EXPECT_EQ(readCellFieldStep(path, "quality", 0, o).size(), m.fileCells);
  }
  EXPECT_GE(files, 20);  // LZ4 and LZMA among them
}

// One <Piece> element: piece k of a strip along x, two tetrahedra with a triangle between them
// (skipped), the second tetrahedron flagged as a ghost when `ghost`; cell data p@t0 = 10 k + c and
// (with two steps) p@t1 = 100 + 10 k + c for cell c, and point data q.
std::string pieceXml(int k, bool ghost, int numSteps = 2) {
  auto num = [](double v) { return std::to_string(v); };
  std::string pts;
  for (auto [x, y, z] : {std::array<int, 3>{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}})
    pts += num(x + 2 * k) + " " + num(y) + " " + num(z) + " ";
  std::string steps;
  for (int s = 0; s < numSteps; ++s) {
    steps += "<DataArray type=\"Float32\" Name=\"p@t" + std::to_string(s) + "\" format=\"ascii\">";
    for (int c = 0; c < 3; ++c) steps += num(100 * s + 10 * k + c) + " ";
    steps += "</DataArray>";
  }
  return "<Piece NumberOfPoints=\"5\" NumberOfCells=\"3\"><PointData>"
         "<DataArray type=\"Float32\" Name=\"q\" format=\"ascii\">1 2 3 4 5</DataArray>"
         "</PointData><CellData>" +
         steps +
         (ghost ? "<DataArray type=\"UInt8\" Name=\"vtkGhostType\" format=\"ascii\">0 0 1"
                  "</DataArray>"
                : "") +
         "</CellData><Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" "
         "format=\"ascii\">" +
         pts +
         "</DataArray></Points><Cells>"
         "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 2 3 0 1 2 1 2 3 4"
         "</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">4 7 11"
         "</DataArray><DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">10 5 10"
         "</DataArray></Cells></Piece>";
}

std::string vtuXml(const std::string& pieces) {
  return "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\"><UnstructuredGrid>" + pieces +
         "</UnstructuredGrid></VTKFile>";
}

// A .pvtu of three piece files (the last holding two <Piece>s, the second a ghost cell), written
// under `dir` with names starting `stem`.
void writeStrip(const std::string& dir, const std::string& stem, int steps = 2) {
  writeText(dir + "/" + stem + "_0.vtu", vtuXml(pieceXml(0, false, steps)));
  writeText(dir + "/" + stem + "_1.vtu", vtuXml(pieceXml(1, true, steps)));
  writeText(dir + "/" + stem + "_2.vtu",
            vtuXml(pieceXml(2, false, steps) + pieceXml(3, false, steps)));
  std::string index = "<VTKFile type=\"PUnstructuredGrid\"><PUnstructuredGrid>";
  for (int k = 0; k < 3; ++k)
    index += "<Piece Source=\"" + stem + "_" + std::to_string(k) + ".vtu\"/>";
  writeText(dir + "/" + stem + ".pvtu", index + "</PUnstructuredGrid></VTKFile>");
}

TEST(CellStep, SomePiecesOfAPvtuWithSkippedAndGhostCells) {
  const std::string dir = sm::test::outputDir("CellStep.Pvtu");
  writeStrip(dir, "strip");
  const std::string path = dir + "/strip.pvtu";
  for (std::vector<int> pieces : {std::vector<int>{}, {1, 2}, {2}, {0, 1}}) {
    SCOPED_TRACE(::testing::PrintToString(pieces));
    ReadOptions whole = cellsKept("p");
    whole.pieces = pieces;
    const mesh::UnstructuredMesh all = readMesh(path, whole);  // every step in memory
    ASSERT_EQ(all.cellFields.size(), 1u);
    ASSERT_EQ(all.cellFields[0].steps.size(), 2u);
    ReadOptions first = whole;
    first.step = 0;  // as a stream reads it: step 0 only, with the cells' origins
    const mesh::UnstructuredMesh m = readMesh(path, first);
    ASSERT_EQ(m.cellOrigin.size(), m.numCells());
    for (size_t s = 0; s < 2; ++s)
      expectSameBits(readCellFieldStep(path, "p", s, whole, m.cellOrigin),
                     flatStep(all.cellFields[0], s));
  }
  // Every piece: the ghost (10 k + 2 for k = 1) is not among the values, each other tetrahedron is.
  const mesh::UnstructuredMesh m = readMesh(path, cellsKept("p"));
  EXPECT_EQ(m.fileCells, 12u);
  EXPECT_EQ(readCellFieldStep(path, "p", 1, {}, m.cellOrigin),
            (std::vector<float>{100, 102, 110, 120, 122, 130, 132}));
}

TEST(CellStep, SeriesStepsComeFromTheirFiles) {
  const std::string dir = sm::test::outputDir("CellStep.Series");
  writeStrip(dir, "a", 1);
  writeStrip(dir, "b", 1);
  // Step 1 of the series is b.pvtu's p@t0; make it differ from a's by editing one value.
  std::string b1 = vtuXml(pieceXml(1, true, 1));
  b1.replace(b1.find(">10.000000 "), 11, ">77.000000 ");
  writeText(dir + "/b_1.vtu", b1);
  writeText(dir + "/s.pvd",
            "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"0\" file=\"a.pvtu\"/>"
            "<DataSet timestep=\"1\" file=\"b.pvtu\"/></Collection></VTKFile>");
  ReadOptions o = cellsKept("p");
  o.pieces = {1};
  ReadOptions first = o;
  first.step = 0;
  const mesh::UnstructuredMesh m = readMesh(dir + "/s.pvd", first);
  EXPECT_EQ(readCellFieldStep(dir + "/s.pvd", "p", 1, o, m.cellOrigin),
            (std::vector<float>{77}));  // piece 1's second tetrahedron is a ghost
  EXPECT_NE(fileErrorOf([&] {
              readCellFieldStep(dir + "/s.pvd", "p", 2, o, m.cellOrigin);
            }).find("field 'p' has 2 time steps (0 .. 1), not step 2"),
            std::string::npos);
  // A step holding the field as point data is refused when the series is listed, before any step
  // is read.
  std::string pointData = vtuXml(pieceXml(0, false, 1));
  const std::string open = "<PointData>";
  pointData.replace(pointData.find(open), open.size(),
                    open +
                        "<DataArray type=\"Float32\" Name=\"p\" format=\"ascii\">1 2 3 4 5"
                        "</DataArray>");
  pointData.replace(pointData.find("Name=\"p@t0\""), 11, "Name=\"x@t0\"");
  writeText(dir + "/pd_0.vtu", pointData);
  writeText(dir + "/pd.pvd",
            "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"0\" file=\"a_0.vtu\"/>"
            "<DataSet timestep=\"1\" file=\"pd_0.vtu\"/></Collection></VTKFile>");
  ReadOptions p;
  p.fields = {"p"};
  EXPECT_NE(fileErrorOf([&] {
              listFieldSteps(dir + "/pd.pvd", p);
            }).find("step 1 ('" + dir + "/pd_0.vtu') holds 'p' as point data, step 0 as cell data"),
            std::string::npos);
}

TEST(CellStep, WrongDataMissingStepsAndOtherFormatsAreNamed) {
  const std::string dir = sm::test::outputDir("CellStep.Errors");
  writeText(dir + "/one.vtu", vtuXml(pieceXml(0, false)));
  const std::string one = dir + "/one.vtu";
  EXPECT_NE(fileErrorOf([&] {
              readCellFieldStep(one, "p", 2);
            }).find("has no cell array 'p@t2' (field 'p' has 2 time steps)"),
            std::string::npos);
  EXPECT_NE(fileErrorOf([&] {
              readCellFieldStep(one, "q", 0);
            }).find("holds 'q' as point data, not cell data"),
            std::string::npos);
  EXPECT_NE(fileErrorOf([&] { readCellFieldStep(one, "zz", 0); }).find("has no cell array 'zz'"),
            std::string::npos);
  EXPECT_NE(fileErrorOf([&] {
              readFieldStep(one, "p", 0);
            }).find("holds 'p' as cell data, not point data"),
            std::string::npos);
  // A map naming a cell the file does not have (the file shrank since its mesh was read).
  const std::vector<uint32_t> map{0, 5};
  EXPECT_NE(fileErrorOf([&] {
              readCellFieldStep(one, "p", 0, {}, map);
            }).find("has 3 cells in the pieces read, fewer than when its mesh was read"),
            std::string::npos);
  try {
    readCellFieldStep(test::fixturePath("mesh_v42_ascii.vtk"), "quality", 0);
    ADD_FAILURE() << "a legacy file was read one step at a time";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("from .vtu and .pvtu files and series of them only"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace sm::io
