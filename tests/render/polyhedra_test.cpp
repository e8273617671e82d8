// Polyhedron cells rendered: a block of cubes written as VTK polyhedra (points numbered at random,
// so that no two neighbours list a shared face alike) and the same block written as hexahedra.
// For a linear field both interpolations are exact, so the images agree with each other and with
// the CPU reference; and the split conforms, so every ray through the block is one segment (a
// face cut differently by its two cells would be a shell inside the block and end a segment).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <numeric>
#include <random>

#include "io/mesh_io.h"
#include "render_harness.h"
#include "scene/camera.h"
#include "support/test_support.h"

namespace sm::render {
namespace {

std::string dataArray(const char* type, const char* name, const std::string& values,
                      int comps = 1) {
  return std::string("<DataArray type=\"") + type + "\" Name=\"" + name +
         "\" NumberOfComponents=\"" + std::to_string(comps) + "\" format=\"ascii\">" + values +
         "</DataArray>";
}

// One ascii piece: points `xyz`, point field f, cells as VTK lists them (`polyArrays`: the
// polyhedra's face arrays, if any).
std::string asciiVtu(size_t numPoints, size_t numCells, const std::string& xyz,
                     const std::string& f, const std::string& conn, const std::string& offsets,
                     const std::string& types, const std::string& polyArrays = {}) {
  return "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\"><UnstructuredGrid><Piece "
         "NumberOfPoints=\"" +
         std::to_string(numPoints) + "\" NumberOfCells=\"" + std::to_string(numCells) +
         "\"><PointData>" + dataArray("Float64", "f", f) + "</PointData><Points>" +
         dataArray("Float64", "Points", xyz, 3) + "</Points><Cells>" +
         dataArray("Int64", "connectivity", conn) + dataArray("Int64", "offsets", offsets) +
         dataArray("UInt8", "types", types) + polyArrays +
         "</Cells></Piece></UnstructuredGrid></VTKFile>";
}

// An n^3 block of unit cubes as an ascii .vtu: hexahedra, or polyhedra with their six faces.
std::string cubeBlock(int n, bool polyhedra) {
  const int m = n + 1;
  std::vector<int> id(size_t(m * m * m));
  std::iota(id.begin(), id.end(), 0);
  std::shuffle(id.begin(), id.end(), std::mt19937(11));
  std::vector<double> xyz(id.size() * 3);
  auto at = [&](int i, int j, int k) { return id[size_t((k * m + j) * m + i)]; };
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const size_t p = size_t(at(i, j, k)) * 3;
        xyz[p] = i, xyz[p + 1] = j, xyz[p + 2] = k;
      }
  const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                           {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  std::string conn, offsets, types, stream, faceEnds;
  int cells = 0;
  size_t streamLength = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int c[8] = {
            at(i, j, k),     at(i + 1, j, k),     at(i + 1, j + 1, k),     at(i, j + 1, k),
            at(i, j, k + 1), at(i + 1, j, k + 1), at(i + 1, j + 1, k + 1), at(i, j + 1, k + 1)};
        for (int v : c) conn += std::to_string(v) + " ";
        offsets += std::to_string(8 * ++cells) + " ";
        types += polyhedra ? "42 " : "12 ";
        stream += "6 ";
        for (const auto& f : faces) {
          stream += "4 ";
          for (int v : f) stream += std::to_string(c[v]) + " ";
        }
        streamLength += 1 + 6 * 5;
        faceEnds += std::to_string(streamLength) + " ";
      }
  std::string points, values;
  for (size_t p = 0; p < id.size(); ++p) {
    points += std::to_string(xyz[3 * p]) + " " + std::to_string(xyz[3 * p + 1]) + " " +
              std::to_string(xyz[3 * p + 2]) + " ";
    values += std::to_string(xyz[3 * p] + 2 * xyz[3 * p + 1] + 3 * xyz[3 * p + 2]) + " ";
  }
  return asciiVtu(
      id.size(), size_t(cells), points, values, conn, offsets, types,
      polyhedra ? dataArray("Int64", "faces", stream) + dataArray("Int64", "faceoffsets", faceEnds)
                : std::string());
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Renders field f (x + 2y + 3z, mapped over [0, hi]) of `m` at a step fine enough for the
// reference's tolerance, from the iso view, and checks it: no validation message, no lost ray,
// every ray through the volume one segment (no shell inside it: a conforming split), and the image
// against the CPU reference. Returns the image.
scene::Image renderConforming(const mesh::UnstructuredMesh& m, double hi, const std::string& name) {
  RenderSettings s;
  s.width = 64;
  s.height = 48;
  s.camera = scene::frameBounds(m.bounds(), scene::ViewPreset::Iso, double(s.width) / s.height);
  s.transferFunction = scene::makeTransferFunction("viridis");
  s.transferFunction.lo = 0;
  s.transferFunction.hi = hi;
  s.transferFunction.unitDistance = m.bounds().diagonal() / 4;
  s.dt = 0.05;
  s.integration = Integration::Sampled;  // the grid reference's samples
  s.earlyTermination = 2.0;
  s.keepSegments = true;
  auto gpu = test::renderOnGpu(m, "f", s);
  EXPECT_EQ(gpu.validationErrors, 0u) << name;
  EXPECT_EQ(gpu.frame.counters.lostRays, 0u) << name;
  size_t most = 0, hit = 0;
  for (const auto& px : gpu.segments) {
    most = std::max(most, px.size());
    hit += px.empty() ? 0 : 1;
  }
  EXPECT_GT(hit, size_t(s.width * s.height / 4)) << name;
  EXPECT_EQ(most, 1u) << name << ": a ray met a shell inside the volume";
  test::expectImagesClose(name, test::renderReference(m, m.fields[0].steps[0], s), gpu.image);
  return gpu.image;
}

TEST(Polyhedra, BlockOfPolyhedraRendersAsItsHexahedra) {
  const std::string dir = test::outputDir("Polyhedra.Render");
  const int n = 4;
  std::vector<mesh::UnstructuredMesh> meshes;
  for (bool poly : {true, false}) {
    const std::string path = dir + (poly ? "/poly.vtu" : "/hex.vtu");
    writeText(path, cubeBlock(n, poly));
    meshes.push_back(io::readMesh(path));
  }
  ASSERT_EQ(meshes[0].numCells(mesh::CellType::Tet), uint64_t(6 * n * n * n));
  ASSERT_EQ(meshes[0].skipped.polyhedraSplit, uint64_t(n * n * n));
  ASSERT_EQ(meshes[1].numCells(mesh::CellType::Hex), uint64_t(n * n * n));

  const scene::Image poly = renderConforming(meshes[0], 6.0 * n, "polyhedra_block");
  const scene::Image hex = renderConforming(meshes[1], 6.0 * n, "polyhedra_block_hex");
  test::expectImagesClose("polyhedra_vs_hexahedra", hex, poly);
}

// Polyhedra given as face lists, in an ascii .vtu with the linear field f = x + 2y + 3z.
std::string polyhedraVtu(const std::vector<glm::dvec3>& points,
                         const std::vector<std::vector<std::vector<int>>>& cells) {
  std::string xyz, f, conn, offsets, types, stream, ends;
  for (const auto& p : points) {
    xyz += std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + " ";
    f += std::to_string(p.x + 2 * p.y + 3 * p.z) + " ";
  }
  size_t nconn = 0, nstream = 0;
  for (const auto& cell : cells) {
    std::vector<int> used;
    stream += std::to_string(cell.size()) + " ";
    ++nstream;
    for (const auto& face : cell) {
      stream += std::to_string(face.size()) + " ";
      nstream += 1 + face.size();
      for (int v : face) {
        stream += std::to_string(v) + " ";
        if (std::find(used.begin(), used.end(), v) == used.end()) used.push_back(v);
      }
    }
    for (int v : used) conn += std::to_string(v) + " ";
    nconn += used.size();
    offsets += std::to_string(nconn) + " ";
    types += "42 ";
    ends += std::to_string(nstream) + " ";
  }
  return asciiVtu(points.size(), cells.size(), xyz, f, conn, offsets, types,
                  dataArray("Int64", "faces", stream) + dataArray("Int64", "faceoffsets", ends));
}

// Where a refined region meets a coarse cell, as snappyHexMesh leaves it: the coarse cube
// [0,2]^3 has its x = 2 side as the four faces of the four unit cubes beyond it, and the points
// on that side's edges in the faces around it (pentagons). Every cell a polyhedron. The split
// still conforms (one segment per ray) and the image is the CPU reference's.
TEST(Polyhedra, RefinementInterfaceWithPointsOnEdges) {
  std::vector<glm::dvec3> points;
  std::map<std::array<int, 3>, int> index;
  auto pt = [&](int x, int y, int z) {  // on a grid of unit spacing
    auto [it, added] = index.try_emplace({x, y, z}, int(points.size()));
    if (added) points.push_back(glm::dvec3(x, y, z));
    return it->second;
  };
  // A unit cube at (x, y, z) with outward faces.
  auto cube = [&](int x, int y, int z) {
    const int c[8] = {
        pt(x, y, z),     pt(x + 1, y, z),     pt(x + 1, y + 1, z),     pt(x, y + 1, z),
        pt(x, y, z + 1), pt(x + 1, y, z + 1), pt(x + 1, y + 1, z + 1), pt(x, y + 1, z + 1)};
    const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                             {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    std::vector<std::vector<int>> out;
    for (const auto& f : faces) out.push_back({c[f[0]], c[f[1]], c[f[2]], c[f[3]]});
    return out;
  };
  std::vector<std::vector<std::vector<int>>> cells;
  // The coarse cube: x = 0 side, the x = 2 side as four quads, four pentagons around.
  cells.push_back({{pt(0, 0, 0), pt(0, 0, 2), pt(0, 2, 2), pt(0, 2, 0)},
                   {pt(2, 0, 0), pt(2, 1, 0), pt(2, 1, 1), pt(2, 0, 1)},
                   {pt(2, 1, 0), pt(2, 2, 0), pt(2, 2, 1), pt(2, 1, 1)},
                   {pt(2, 0, 1), pt(2, 1, 1), pt(2, 1, 2), pt(2, 0, 2)},
                   {pt(2, 1, 1), pt(2, 2, 1), pt(2, 2, 2), pt(2, 1, 2)},
                   {pt(0, 0, 0), pt(2, 0, 0), pt(2, 0, 1), pt(2, 0, 2), pt(0, 0, 2)},    // y = 0
                   {pt(0, 2, 0), pt(0, 2, 2), pt(2, 2, 2), pt(2, 2, 1), pt(2, 2, 0)},    // y = 2
                   {pt(0, 0, 0), pt(0, 2, 0), pt(2, 2, 0), pt(2, 1, 0), pt(2, 0, 0)},    // z = 0
                   {pt(0, 0, 2), pt(2, 0, 2), pt(2, 1, 2), pt(2, 2, 2), pt(0, 2, 2)}});  // z = 2
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y) cells.push_back(cube(2, y, z));
  const std::string path = test::outputDir("Polyhedra.Refinement") + "/refined.vtu";
  writeText(path, polyhedraVtu(points, cells));
  const mesh::UnstructuredMesh m = io::readMesh(path);
  ASSERT_EQ(m.skipped.polyhedraSplit, 5u);
  ASSERT_EQ(m.skipped.polyhedra, 0u);

  renderConforming(m, 15, "polyhedra_refinement");
}

// A block of cube polyhedra in two .pvtu pieces, each numbering its points its own (random) way:
// the pieces are welded on read, and the faces between them, split by each piece on its own, are
// still cut alike (by position, not id), so no ray meets a shell where the pieces meet.
TEST(Polyhedra, PiecesOfAPvtuMeetWithoutShells) {
  const std::string dir = test::outputDir("Polyhedra.Pieces");
  std::mt19937 rng(5);
  for (int piece = 0; piece < 2; ++piece) {
    std::vector<glm::dvec3> points;
    std::map<std::array<int, 3>, int> index;
    std::vector<std::array<int, 3>> grid;
    for (int x = 2 * piece; x <= 2 * piece + 2; ++x)
      for (int y = 0; y <= 2; ++y)
        for (int z = 0; z <= 2; ++z) grid.push_back({x, y, z});
    std::shuffle(grid.begin(), grid.end(), rng);
    for (const auto& g : grid) {
      index[g] = int(points.size());
      points.push_back(glm::dvec3(g[0], g[1], g[2]));
    }
    auto pt = [&](int x, int y, int z) { return index.at({x, y, z}); };
    std::vector<std::vector<std::vector<int>>> cells;
    for (int x = 2 * piece; x < 2 * piece + 2; ++x)
      for (int y = 0; y < 2; ++y)
        for (int z = 0; z < 2; ++z) {
          const int c[8] = {
              pt(x, y, z),     pt(x + 1, y, z),     pt(x + 1, y + 1, z),     pt(x, y + 1, z),
              pt(x, y, z + 1), pt(x + 1, y, z + 1), pt(x + 1, y + 1, z + 1), pt(x, y + 1, z + 1)};
          const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                   {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
          std::vector<std::vector<int>> cell;
          for (const auto& f : faces) cell.push_back({c[f[0]], c[f[1]], c[f[2]], c[f[3]]});
          cells.push_back(cell);
        }
    writeText(dir + "/piece" + std::to_string(piece) + ".vtu", polyhedraVtu(points, cells));
  }
  writeText(dir + "/block.pvtu",
            "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\"><PUnstructuredGrid "
            "GhostLevel=\"0\"><PPointData><PDataArray type=\"Float64\" Name=\"f\"/></PPointData>"
            "<PPoints><PDataArray type=\"Float64\" NumberOfComponents=\"3\"/></PPoints>"
            "<Piece Source=\"piece0.vtu\"/><Piece Source=\"piece1.vtu\"/></PUnstructuredGrid>"
            "</VTKFile>");
  const mesh::UnstructuredMesh m = io::readMesh(dir + "/block.pvtu");
  ASSERT_EQ(m.skipped.polyhedraSplit, 16u);
  ASSERT_EQ(m.numPoints(), 45u);  // 2 x 27 welded along the 9 points of x = 2

  // One cluster (the pieces are clusters 0 and 1 when read; join them so that the walk has to
  // cross where they meet rather than stop at a cluster's shell).
  mesh::UnstructuredMesh one = m;
  for (auto& c : one.clusters) std::fill(c.begin(), c.end(), 0);
  renderConforming(one, 14, "polyhedra_pieces");
}

}  // namespace
}  // namespace sm::render
