#include "io_test_util.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>

#include "mesh/element_geometry.h"
#include "mesh/mesh_builder.h"

namespace sm::io::test {

using mesh::CellType;

std::string fixturePath(const std::string& file) {
  return std::string(SHELLMARCH_IO_TEST_DATA) + "/" + file;
}

void expectGhostCellsSkipped(const std::string& path, std::vector<double> keptApexZ) {
  testing::internal::CaptureStderr();
  mesh::UnstructuredMesh m = readMesh(path);
  const std::string err = testing::internal::GetCapturedStderr();
  ASSERT_EQ(m.numCells(), keptApexZ.size());
  std::vector<double> apexZ;
  for (uint64_t i = 0; i < m.numCells(CellType::Tet); ++i)
    for (uint32_t v : cellIds(m, CellType::Tet, i))
      if (m.points[v].z > 0.0) apexZ.push_back(m.points[v].z);
  std::sort(apexZ.begin(), apexZ.end());
  EXPECT_EQ(apexZ, keptApexZ);
  EXPECT_NE(err.find("skipped 1 ghost cells (vtkGhostType DUPLICATECELL"), std::string::npos)
      << err;
  EXPECT_NE(err.find("skipped 1 hidden cells (vtkGhostType HIDDENCELL)"), std::string::npos) << err;
}

std::vector<uint32_t> cellIds(const mesh::UnstructuredMesh& m, CellType t, uint64_t i) {
  const uint32_t nv = mesh::numVerts(t);
  const auto& c = m.cells[mesh::typeIndex(t)];
  return {c.begin() + i * nv, c.begin() + (i + 1) * nv};
}

void expectAllPositive(const mesh::UnstructuredMesh& m) {
  for (CellType t : mesh::kAllCellTypes) {
    const uint32_t nv = mesh::numVerts(t);
    for (uint64_t i = 0; i < m.numCells(t); ++i)
      ASSERT_GT(mesh::signedVolume(t, {m.cells[mesh::typeIndex(t)].data() + i * nv, nv}, m.points),
                0.0)
          << mesh::cellTypeName(t) << " " << i;
  }
}

void expectFixtureGeometry(const mesh::UnstructuredMesh& m) {
  ASSERT_EQ(m.numPoints(), 13u);
  EXPECT_EQ(m.points[8], glm::dvec3(1.5, 0.5, 0.5));
  EXPECT_EQ(m.points[12], glm::dvec3(0.5, -0.5, 0.5));
  ASSERT_EQ(m.numCells(CellType::Hex), 1u);
  ASSERT_EQ(m.numCells(CellType::Pyramid), 1u);
  ASSERT_EQ(m.numCells(CellType::Wedge), 1u);
  ASSERT_EQ(m.numCells(CellType::Tet), 3u);
  EXPECT_EQ(cellIds(m, CellType::Hex, 0), (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(cellIds(m, CellType::Pyramid, 0), (std::vector<uint32_t>{1, 2, 6, 5, 8}));
  EXPECT_EQ(cellIds(m, CellType::Wedge, 0), (std::vector<uint32_t>{3, 7, 9, 2, 6, 10}));
  EXPECT_EQ(cellIds(m, CellType::Tet, 0), (std::vector<uint32_t>{0, 4, 3, 11}));
  EXPECT_EQ(cellIds(m, CellType::Tet, 1), (std::vector<uint32_t>{0, 1, 4, 12}));  // was 0 4 1 12
  EXPECT_EQ(cellIds(m, CellType::Tet, 2),
            (std::vector<uint32_t>{0, 1, 3, 4}));  // quadratic corners
  EXPECT_EQ(m.invertedFixed, 1u);
  EXPECT_EQ(m.skipped.surface, 1u);
  EXPECT_EQ(m.skipped.lineOrVertex, 1u);
  EXPECT_EQ(m.skipped.quadraticReduced, 1u);
  EXPECT_EQ(m.skipped.polyhedra + m.skipped.other, 0u);
  EXPECT_EQ(m.clusters[mesh::typeIndex(CellType::Hex)], (std::vector<int32_t>{0}));
  EXPECT_EQ(m.clusters[mesh::typeIndex(CellType::Pyramid)], (std::vector<int32_t>{1}));
  EXPECT_EQ(m.clusters[mesh::typeIndex(CellType::Wedge)], (std::vector<int32_t>{1}));
  EXPECT_EQ(m.clusters[mesh::typeIndex(CellType::Tet)], (std::vector<int32_t>{2, 2, 3}));
  EXPECT_EQ(m.numClusters(), 4);
}

void expectFixtureMesh(const mesh::UnstructuredMesh& m) {
  expectFixtureGeometry(m);
  ASSERT_EQ(m.fields.size(), 4u);
  const mesh::Field* p = m.findField("pressure");
  const mesh::Field* v = m.findField("velocity");
  const mesh::Field* t = m.findField("temp");
  const mesh::Field* c = m.findField("count");
  ASSERT_TRUE(p && v && t && c);
  ASSERT_EQ(p->numSteps(), 1u);
  ASSERT_EQ(t->numSteps(), 3u);
  for (int i = 0; i < 13; ++i) {
    EXPECT_FLOAT_EQ(p->steps[0][i], 1.0f + 0.5f * i);
    EXPECT_FLOAT_EQ(v->steps[0][i], float(std::sqrt(6.0) * i));
    EXPECT_FLOAT_EQ(c->steps[0][i], 3.0f * i);
    for (int s = 0; s < 3; ++s) EXPECT_FLOAT_EQ(t->steps[s][i], float(i + 100 * s));
  }
  EXPECT_EQ(m.timeValues, (std::vector<double>{0.0, 0.25, 1.0}));
}

std::vector<std::vector<double>> canonicalCells(const mesh::UnstructuredMesh& m) {
  std::vector<std::vector<double>> out;
  for (CellType t : mesh::kAllCellTypes) {
    const uint32_t nv = mesh::numVerts(t);
    for (uint64_t c = 0; c < m.numCells(t); ++c) {
      std::vector<double> r = {double(mesh::typeIndex(t)),
                               double(m.clusters[mesh::typeIndex(t)][c])};
      for (uint32_t k = 0; k < nv; ++k) {
        uint32_t id = m.cells[mesh::typeIndex(t)][c * nv + k];
        r.insert(r.end(), {m.points[id].x, m.points[id].y, m.points[id].z});
        for (const auto& f : m.fields)
          for (const auto& s : f.steps) r.push_back(s[id]);
      }
      for (const auto& f : m.cellFields)
        for (const auto& s : f.steps) r.push_back(s[mesh::typeIndex(t)][c]);
      out.push_back(std::move(r));
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<uint8_t> readBytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

void writeBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

void writeText(const std::string& path, const std::string& text) {
  writeBytes(path, std::vector<uint8_t>(text.begin(), text.end()));
}

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

}  // namespace sm::io::test
