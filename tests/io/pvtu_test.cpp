#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "io/mesh_io.h"
#include "io_core/weld.h"
#include "io_test_util.h"
#include "support/allocation_cap.h"
#include "support/test_support.h"

namespace sm::io {
namespace {

using mesh::CellType;
using test::cellIds;
using test::fileErrorOf;
using test::fixturePath;

std::vector<uint32_t> sorted(std::vector<uint32_t> v) {
  std::sort(v.begin(), v.end());
  return v;
}

std::vector<uint32_t> pick(const std::vector<uint32_t>& ids, std::initializer_list<int> at) {
  std::vector<uint32_t> r;
  for (int i : at) r.push_back(ids[i]);
  return sorted(r);
}

// weld.pvtu: piece 0 the hexahedron, piece 1 the pyramid and wedge on two of its faces, piece 2
// a tetrahedron on a third face; every piece has its own copy of the points it uses.
TEST(PvtuReader, WeldsPiecesSoThatSharedFacesShareVertexIds) {
  EXPECT_EQ(countPieces(fixturePath("weld.pvtu")), 3);
  mesh::UnstructuredMesh m = readMesh(fixturePath("weld.pvtu"));
  EXPECT_EQ(m.numPoints(), 12u);  // 8 + 9 + 4 copies of 12 distinct points
  ASSERT_EQ(m.numCells(), 4u);
  const auto hex = cellIds(m, CellType::Hex, 0);
  const auto pyr = cellIds(m, CellType::Pyramid, 0);
  const auto wedge = cellIds(m, CellType::Wedge, 0);
  const auto tet = cellIds(m, CellType::Tet, 0);
  EXPECT_EQ(pick(pyr, {0, 1, 2, 3}), pick(hex, {1, 2, 6, 5}));    // the +x face
  EXPECT_EQ(pick(wedge, {0, 1, 3, 4}), pick(hex, {3, 7, 2, 6}));  // the +y face
  EXPECT_EQ(pick(tet, {0, 1, 2}), pick(hex, {0, 4, 3}));          // a triangle on the -x face
  EXPECT_EQ(m.points[pyr[4]], glm::dvec3(1.5, 0.5, 0.5));
  EXPECT_EQ(m.clusters[mesh::typeIndex(CellType::Hex)][0], 0);
  EXPECT_EQ(m.clusters[mesh::typeIndex(CellType::Pyramid)][0], 1);
  EXPECT_EQ(m.clusters[mesh::typeIndex(CellType::Wedge)][0], 1);
  EXPECT_EQ(m.clusters[mesh::typeIndex(CellType::Tet)][0], 2);
  ASSERT_EQ(m.fields.size(), 1u);
  test::expectAllPositive(m);
}

TEST(PvtuReader, WeldedFieldValuesFollowThePoints) {
  mesh::UnstructuredMesh m = readMesh(fixturePath("weld.pvtu"));
  const glm::dvec3 original[12] = {{0, 0, 0},       {1, 0, 0},     {1, 1, 0},     {0, 1, 0},
                                   {0, 0, 1},       {1, 0, 1},     {1, 1, 1},     {0, 1, 1},
                                   {1.5, 0.5, 0.5}, {0, 1.5, 0.5}, {1, 1.5, 0.5}, {-0.5, 0.5, 0.5}};
  for (uint32_t p = 0; p < m.numPoints(); ++p) {
    int i = int(std::find(original, original + 12, m.points[p]) - original);
    ASSERT_LT(i, 12);
    EXPECT_EQ(m.fields[0].steps[0][p], 1.0f + 0.5f * i);
  }
}

TEST(PvtuReader, ReadsASubsetKeepingGlobalPieceNumbers) {
  ReadOptions o;
  o.pieces = {2, 1};
  mesh::UnstructuredMesh m = readMesh(fixturePath("weld.pvtu"), o);
  EXPECT_EQ(m.numPoints(), 12u);  // 9 + 4, sharing one point
  EXPECT_EQ(m.numCells(CellType::Hex), 0u);
  EXPECT_EQ(m.numCells(), 3u);
  EXPECT_EQ(m.clusters[mesh::typeIndex(CellType::Tet)][0], 2);
  EXPECT_EQ(m.numClusters(), 3);
  o.pieces = {2};
  m = readMesh(fixturePath("weld.pvtu"), o);
  EXPECT_EQ(m.numPoints(), 4u);
  EXPECT_EQ(m.numCells(CellType::Tet), 1u);
  EXPECT_EQ(m.clusters[mesh::typeIndex(CellType::Tet)][0], 2);
}

// Ranks share pieces out by the cell counts in the pieces' headers, without reading them.
TEST(PvtuReader, PieceCellCountsComeFromTheHeaders) {
  EXPECT_EQ(pieceCellCounts(fixturePath("weld.pvtu")), (std::vector<uint64_t>{1, 2, 1}));
  EXPECT_NE(fileErrorOf([] { pieceCellCounts(fixturePath("no_such.pvtu")); }).find("no_such.pvtu"),
            std::string::npos);
}

TEST(PvtuReader, BadPieceNumbersAreErrors) {
  ReadOptions o;
  o.pieces = {3};
  std::string msg = fileErrorOf([&] { readMesh(fixturePath("weld.pvtu"), o); });
  EXPECT_NE(msg.find("weld.pvtu"), std::string::npos) << msg;
  EXPECT_NE(msg.find("no piece 3"), std::string::npos) << msg;
  o.pieces = {1, 1};
  EXPECT_NE(fileErrorOf([&] { readMesh(fixturePath("weld.pvtu"), o); }).find("twice"),
            std::string::npos);
}

TEST(PvtuReader, MissingPieceFileIsNamed) {
  const std::string dir = sm::test::outputDir("PvtuReader.MissingPiece");
  test::writeText(dir + "/m.pvtu",
                  "<?xml version=\"1.0\"?><VTKFile type=\"PUnstructuredGrid\" version=\"1.0\">"
                  "<PUnstructuredGrid><Piece Source=\"m/m_0.vtu\"/></PUnstructuredGrid></VTKFile>");
  std::string msg = fileErrorOf([&] { readMesh(dir + "/m.pvtu"); });
  EXPECT_NE(msg.find("m/m_0.vtu"), std::string::npos) << msg;
  EXPECT_EQ(countPieces(dir + "/m.pvtu"), 1);
}

// A piece whose header declares `points` and `cells` but holds one point and no cell data: its
// header is believed only as far as its data goes.
std::string declaredPiece(uint64_t points, uint64_t cells) {
  return concat("<VTKFile type=\"UnstructuredGrid\" version=\"1.0\"><UnstructuredGrid><Piece ",
                "NumberOfPoints=\"", points, "\" NumberOfCells=\"", cells, "\"><Points><DataArray ",
                "type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0</DataArray>",
                "</Points><Cells><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">",
                "</DataArray></Cells></Piece></UnstructuredGrid></VTKFile>\n");
}

// Writes DIR/big.pvtu with pieces a.vtu and b.vtu; returns its path.
std::string twoPieceIndex(const std::string& dir, const std::string& a, const std::string& b) {
  test::writeText(dir + "/a.vtu", a);
  test::writeText(dir + "/b.vtu", b);
  test::writeText(dir + "/big.pvtu",
                  "<?xml version=\"1.0\"?><VTKFile type=\"PUnstructuredGrid\" version=\"1.0\">"
                  "<PUnstructuredGrid><Piece Source=\"a.vtu\"/><Piece Source=\"b.vtu\"/>"
                  "</PUnstructuredGrid></VTKFile>");
  return dir + "/big.pvtu";
}

// One rank's pieces are welded into one mesh with 32-bit vertex ids and point origins: pieces
// that fit alone (2^32 - 1 points and 1) but not together are refused from their headers before
// any is read, naming the limit and what would fit; either piece alone is read (and fails here
// only on the data it lacks).
TEST(PvtuReader, PiecesPast32BitIdsTogetherAreRefusedBeforeReading) {
  sm::test::AllocationCap cap;
  const std::string dir = sm::test::outputDir("PvtuReader.PiecesPast32BitIds");
  const std::string index =
      twoPieceIndex(dir, declaredPiece(0xFFFFFFFFull, 0), declaredPiece(1, 0));
  EXPECT_EQ(fileErrorOf([&] { readMesh(index); }),
            index +
                ": the pieces to be read declare 4294967296 points: vertex ids are 32-bit, so "
                "one mesh holds at most 4294967295 (use more ranks)");
  ReadOptions first;
  first.pieces = {0};
  EXPECT_NE(fileErrorOf([&] { readMesh(index, first); }).find("a.vtu: points: declares"),
            std::string::npos);
  ReadOptions second;
  second.pieces = {1};
  EXPECT_EQ(readMesh(index, second).numPoints(), 1u);
}

// Cell origins (kept for streamed cell data) are 32-bit: pieces that together declare 2^32 cells
// are refused before any is read when origins are asked for; otherwise cell counts are 64-bit and
// the read goes on (to the data these pieces lack).
TEST(PvtuReader, CellOriginsPast32BitsTogetherAreRefusedBeforeReading) {
  sm::test::AllocationCap cap;
  const std::string dir = sm::test::outputDir("PvtuReader.CellOriginsPast32Bits");
  const std::string index =
      twoPieceIndex(dir, declaredPiece(1, 0xFFFFFFFFull), declaredPiece(1, 1));
  ReadOptions origins;
  origins.cellOrigins = true;
  const std::string msg = fileErrorOf([&] { readMesh(index, origins); });
  EXPECT_EQ(msg.rfind(index + ": the pieces to be read declare 4294967296 cells", 0), 0u) << msg;
  EXPECT_NE(msg.find("use more ranks"), std::string::npos) << msg;
  EXPECT_NE(fileErrorOf([&] { readMesh(index); }).find("a.vtu: "), std::string::npos);
}

// A piece that is itself a .pvtu index is named as such; the advice for a parallel file named
// .vtu ("give it the .pvtu extension") does not apply to a piece.
TEST(PvtuReader, APieceThatIsItselfAPvtuIsNamed) {
  const std::string dir = sm::test::outputDir("PvtuReader.NestedPvtu");
  const std::string index =
      "<?xml version=\"1.0\"?><VTKFile type=\"PUnstructuredGrid\" version=\"1.0\">"
      "<PUnstructuredGrid><Piece Source=\"inner.vtu\"/></PUnstructuredGrid></VTKFile>";
  test::writeText(dir + "/outer.pvtu", index);
  test::writeText(dir + "/inner.vtu", index);
  std::string msg = fileErrorOf([&] { readMesh(dir + "/outer.pvtu"); });
  EXPECT_NE(msg.find("inner.vtu"), std::string::npos) << msg;
  EXPECT_NE(msg.find("is itself a .pvtu index"), std::string::npos) << msg;
  EXPECT_EQ(msg.find("give it the .pvtu extension"), std::string::npos) << msg;
  // Read on its own, the same file gets the advice.
  msg = fileErrorOf([&] { readMesh(dir + "/inner.vtu"); });
  EXPECT_NE(msg.find("give it the .pvtu extension"), std::string::npos) << msg;
}

// One tetrahedron shifted by `dx`, with point arrays `arrays` ("NAME:COMPONENTS" each), ascii.
std::string asciiTet(double dx, std::initializer_list<std::string> arrays) {
  std::string data;
  for (const std::string& a : arrays) {
    const std::string name = a.substr(0, a.find(':'));
    const int comps = std::stoi(a.substr(a.find(':') + 1));
    data += "<DataArray type=\"Float32\" Name=\"" + name + "\" NumberOfComponents=\"" +
            std::to_string(comps) + "\" format=\"ascii\">";
    for (int i = 0; i < 4 * comps; ++i) data += std::to_string(1 + i / comps) + " ";
    data += "</DataArray>";
  }
  const std::string x = std::to_string(dx), x1 = std::to_string(dx + 1);
  return "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\"><UnstructuredGrid>"
         "<Piece NumberOfPoints=\"4\" NumberOfCells=\"1\"><Points><DataArray type=\"Float64\" "
         "NumberOfComponents=\"3\" format=\"ascii\">" +
         x + " 0 0 " + x1 + " 0 0 " + x + " 1 0 " + x +
         " 0 1</DataArray></Points><Cells>"
         "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2 3</DataArray>"
         "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">4</DataArray>"
         "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">10</DataArray></Cells>"
         "<PointData>" +
         data + "</PointData></Piece></UnstructuredGrid></VTKFile>";
}

// A field that is a scalar in one piece and a vector (read as its magnitude) in another would weld
// without a seam into one wrong field: refused, naming the piece, against the index's declaration
// (which every rank reads, so ranks reading other pieces refuse alike) or, where the index declares
// nothing, against the first piece read. (Steps of one file that differ are refused by name.)
TEST(PvtuReader, AFieldWithOtherComponentsInOnePieceIsRefused) {
  const std::string dir = sm::test::outputDir("PvtuReader.Components");
  test::writeText(dir + "/p0.vtu", asciiTet(0, {"f:1"}));
  test::writeText(dir + "/p1.vtu", asciiTet(2, {"f:3"}));
  const std::string pieces = "<Piece Source=\"p0.vtu\"/><Piece Source=\"p1.vtu\"/>";
  test::writeText(dir + "/declared.pvtu",
                  "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\"><PUnstructuredGrid>"
                  "<PPointData><PDataArray type=\"Float32\" Name=\"f\" NumberOfComponents=\"1\"/>"
                  "</PPointData><PPoints><PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>"
                  "</PPoints>" +
                      pieces + "</PUnstructuredGrid></VTKFile>");
  test::writeText(dir + "/bare.pvtu",
                  "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\"><PUnstructuredGrid>" +
                      pieces + "</PUnstructuredGrid></VTKFile>");
  const std::string piece1 = "piece '" + dir + "/p1.vtu' has 3 components in field 'f'";
  ReadOptions second;
  second.pieces = {1};
  for (const ReadOptions& o : {ReadOptions{}, second}) {
    const std::string msg = fileErrorOf([&] { readMesh(dir + "/declared.pvtu", o); });
    EXPECT_NE(msg.find(piece1 + ", the index declares 1: every piece must hold a field alike"),
              std::string::npos)
        << msg;
  }
  const std::string bare = fileErrorOf([&] { readMesh(dir + "/bare.pvtu"); });
  EXPECT_NE(bare.find(piece1 + ", the first piece ('" + dir + "/p0.vtu') 1"), std::string::npos)
      << bare;
  // One component asked for reads alike from both; a piece read alone with nothing declared to
  // compare it with reads as what it is.
  ReadOptions component;
  component.fields = {"f[0]"};
  EXPECT_EQ(readMesh(dir + "/declared.pvtu", component).fields.at(0).steps.at(0).size(), 8u);
  EXPECT_EQ(readMesh(dir + "/bare.pvtu", second).fields.at(0).steps.at(0).at(0),
            float(std::sqrt(3.0)));
  ReadOptions first;
  first.pieces = {0};
  EXPECT_NO_THROW(readMesh(dir + "/declared.pvtu", first));

  test::writeText(dir + "/steps.vtu", asciiTet(0, {"g@t0:1", "g@t1:3"}));
  const std::string steps = fileErrorOf([&] { readMesh(dir + "/steps.vtu"); });
  EXPECT_NE(steps.find("time steps of point array 'g' have 1 and 3 components"), std::string::npos)
      << steps;
}

// Cell data that one piece lacks: a rank reading that piece alone names it as found in neither
// the point nor the cell data of that piece, not as a missing point array.
TEST(PvtuReader, APieceLackingTheCellDataIsNamed) {
  const std::string dir = sm::test::outputDir("PvtuReader.LacksCellData");
  std::string withCells = asciiTet(0, {});
  withCells.insert(withCells.find("</Piece>"),
                   "<CellData><DataArray type=\"Float32\" Name=\"c\" format=\"ascii\">1"
                   "</DataArray></CellData>");
  test::writeText(dir + "/p0.vtu", withCells);
  test::writeText(dir + "/p1.vtu", asciiTet(2, {"f:1"}));
  test::writeText(dir + "/m.pvtu",
                  "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\"><PUnstructuredGrid>"
                  "<Piece Source=\"p0.vtu\"/><Piece Source=\"p1.vtu\"/></PUnstructuredGrid>"
                  "</VTKFile>");
  ReadOptions o;
  o.fields = {"c"};
  o.pieces = {1};
  const std::string msg = fileErrorOf([&] { readMesh(dir + "/m.pvtu", o); });
  EXPECT_NE(msg.find(dir + "/p1.vtu: has no point or cell array 'c' (point arrays: f; cell data: "
                           "none)"),
            std::string::npos)
      << msg;
  o.pieces = {0};
  EXPECT_EQ(readMesh(dir + "/m.pvtu", o).fields.at(0).name, "c");
}

// A multiblock file (.vtm, as VTK's vtkXMLMultiBlockDataWriter and solvers write one) whose
// unstructured grids are the pieces of a .pvtu: the same welded mesh, piece for piece; surfaces
// and empty blocks are left out.
TEST(MultiblockReader, UnstructuredBlocksArePieces) {
  const std::string dir = sm::test::outputDir("MultiblockReader.Blocks");
  writePvtu(dir + "/grid.pvtu", test::makeTestMesh(3, 2));
  test::writeText(dir + "/grid.vtm",
                  "<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\"><vtkMultiBlockDataSet>"
                  "<DataSet index=\"0\" file=\"grid/grid_0.vtu\"/>"
                  "<Block index=\"1\" name=\"boundary\"><DataSet index=\"0\" file=\"wall.vtp\"/>"
                  "<DataSet index=\"1\"/><Piece index=\"0\"><DataSet file=\"grid/grid_1.vtu\"/>"
                  "</Piece></Block></vtkMultiBlockDataSet></VTKFile>");
  const mesh::UnstructuredMesh pvtu = readMesh(dir + "/grid.pvtu");
  const mesh::UnstructuredMesh vtm = readMesh(dir + "/grid.vtm");
  EXPECT_EQ(vtm.points, pvtu.points);
  for (int t = 0; t < mesh::kNumCellTypes; ++t) {
    EXPECT_EQ(vtm.cells[t], pvtu.cells[t]);
    EXPECT_EQ(vtm.clusters[t], pvtu.clusters[t]);
  }
  ASSERT_EQ(vtm.fields.size(), pvtu.fields.size());
  for (size_t f = 0; f < vtm.fields.size(); ++f)
    EXPECT_EQ(vtm.fields[f].steps, pvtu.fields[f].steps);
  EXPECT_EQ(countPieces(dir + "/grid.vtm"), 2);
  EXPECT_TRUE(readsByPiece(dir + "/grid.vtm"));
  EXPECT_EQ(pieceCellCounts(dir + "/grid.vtm"), pieceCellCounts(dir + "/grid.pvtu"));
  EXPECT_EQ(formatDescription(dir + "/grid.vtm"),
            "VTK XML multiblock (.vtm) of unstructured grids");
  ReadOptions second;
  second.pieces = {1};
  EXPECT_EQ(readMesh(dir + "/grid.vtm", second).points,
            readMesh(dir + "/grid.pvtu", second).points);
  EXPECT_EQ(readFieldStep(dir + "/grid.vtm", "g", 1, {}, vtm.pointOrigin), pvtu.fields[1].steps[1]);

  // A .pvtu named by a block gives its pieces; the same mesh again.
  test::writeText(dir + "/nested.vtm",
                  "<VTKFile type=\"vtkMultiBlockDataSet\"><vtkMultiBlockDataSet><Block>"
                  "<DataSet file=\"grid.pvtu\"/></Block></vtkMultiBlockDataSet></VTKFile>");
  EXPECT_EQ(readMesh(dir + "/nested.vtm").points, pvtu.points);

  test::writeText(dir + "/surfaces.vtm",
                  "<VTKFile type=\"vtkMultiBlockDataSet\"><vtkMultiBlockDataSet>"
                  "<DataSet file=\"wall.vtp\"/></vtkMultiBlockDataSet></VTKFile>");
  EXPECT_NE(fileErrorOf([&] {
              readMesh(dir + "/surfaces.vtm");
            }).find("surfaces.vtm: holds no unstructured grid (.vtu or .pvtu data sets)"),
            std::string::npos);
  test::writeText(dir + "/self.vtm",
                  "<VTKFile type=\"vtkMultiBlockDataSet\"><vtkMultiBlockDataSet>"
                  "<DataSet file=\"self.vtm\"/></vtkMultiBlockDataSet></VTKFile>");
  EXPECT_NE(
      fileErrorOf([&] { readMesh(dir + "/self.vtm"); }).find("self.vtm: names itself ('self.vtm')"),
      std::string::npos);
  test::writeText(dir + "/wrong.vtm", "<VTKFile type=\"PolyData\"/>");
  EXPECT_NE(
      fileErrorOf([&] { readMesh(dir + "/wrong.vtm"); }).find("expected 'vtkMultiBlockDataSet'"),
      std::string::npos);
}

TEST(Weld, MergesAcrossPiecesOnlyAndOnlyBitwiseEqualPoints) {
  mesh::UnstructuredMesh a, b;
  a.points = {{0, 0, 0}, {0, 0, 0}, {1, 0, 0}};  // a duplicate inside one piece stays two points
  b.points = {{1, 0, 0}, {0, 0, 0}, {-0.0, 0, 0}, {1, 1e-300, 0}};
  mesh::UnstructuredMesh w = weldPieces("w", {a, b});
  // b's (1,0,0) and (0,0,0) join a's; -0.0 and 1e-300 differ bitwise and stay apart.
  EXPECT_EQ(w.numPoints(), 5u);
}

// Two coincident points of a later piece (a crack or baffle) stay two where an earlier piece has
// the point: the first joins it, the second does not (both joined it before, and a cell of the
// later piece could end with a repeated vertex).
TEST(Weld, APieceTakesAnEarlierPiecesPointOnce) {
  mesh::UnstructuredMesh a, b, c;
  a.points = {{0, 0, 0}, {1, 0, 0}};
  b.points = {{0, 0, 0}, {0, 0, 0}, {2, 0, 0}};
  c.points = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  mesh::UnstructuredMesh w = weldPieces("w", {a, b, c});
  // a: 2 points; b: its first (0,0,0) joins a's, its second is new, (2,0,0) is new; c: its first
  // two join the two existing copies, its third is new.
  EXPECT_EQ(w.numPoints(), 5u);
}

}  // namespace
}  // namespace sm::io
