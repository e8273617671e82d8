#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <tuple>

#include "common/error.h"
#include "gen/generate.h"
#include "gen/grid_mesh.h"
#include "gen/mesh_checks.h"
#include "io/mesh_io.h"

namespace sm::gen {
namespace {

using mesh::CellType;
namespace fs = std::filesystem;

// Fine enough for the nested cluster (a ball a few cells across).
GridMesh smallGrid(int clusters = 8, int steps = 2) {
  return GridMesh({200000, clusters, steps});
}

// The pieces joined into one mesh, points welded where their coordinates are bit-identical (as
// the pieces of one mesh must be for readers to weld them). Field values of welded points are
// checked to agree.
mesh::UnstructuredMesh joined(const GridMesh& g) {
  mesh::UnstructuredMesh all;
  std::map<std::tuple<double, double, double>, uint32_t> ids;
  std::vector<std::vector<float>> values;
  for (int k = 0; k < g.clusters(); ++k) {
    const mesh::UnstructuredMesh p = g.piece(k);
    EXPECT_EQ(p.fields.size(), 4u);
    std::vector<uint32_t> local(p.points.size());
    for (size_t v = 0; v < p.points.size(); ++v) {
      const auto key = std::make_tuple(p.points[v].x, p.points[v].y, p.points[v].z);
      auto [it, fresh] = ids.emplace(key, uint32_t(all.points.size()));
      local[v] = it->second;
      std::vector<float> here;
      for (const mesh::Field& f : p.fields)
        for (const auto& s : f.steps) here.push_back(s[v]);
      if (fresh) {
        all.points.push_back(p.points[v]);
        values.push_back(here);
      } else {
        EXPECT_EQ(values[it->second], here) << "point " << v << " of piece " << k;
      }
    }
    for (int t = 0; t < mesh::kNumCellTypes; ++t) {
      for (uint32_t id : p.cells[t]) all.cells[t].push_back(local[id]);
      for (int32_t c : p.clusters[t]) EXPECT_EQ(c, k);
      all.clusters[t].insert(all.clusters[t].end(), p.clusters[t].begin(), p.clusters[t].end());
    }
  }
  return all;
}

TEST(GridMesh, PiecesMakeOneConformingPositiveMeshOfTheCountsItStates) {
  const GridMesh g = smallGrid();
  ASSERT_GE(g.nestedCluster(), 0);
  const mesh::UnstructuredMesh m = joined(g);
  EXPECT_EQ(m.numCells(), g.elements());
  EXPECT_EQ(m.numPoints(), g.points());
  for (CellType t : mesh::kAllCellTypes) EXPECT_EQ(m.numCells(t), g.elementsOfType(t));
  const test::FaceReport faces = test::matchFaces(m);
  EXPECT_EQ(faces.overShared, 0u);
  EXPECT_EQ(faces.sameWinding, 0u);
  // One closed boundary: the wall, the far field and the two end planes of the annulus.
  const test::SurfaceReport surface = test::analyseSurface(faces.boundaryFaces);
  EXPECT_EQ(surface.components, 1);
  EXPECT_TRUE(surface.closedAndOriented);
  EXPECT_GT(test::minScaledJacobian(m), 0.0);
  // Straight edges between nodes on circles: the annulus between two regular polygons, exactly.
  const double n = g.thetaCells(), polygon = 0.5 * n * std::sin(2.0 * std::numbers::pi / n);
  const mesh::Bounds b = g.bounds();
  EXPECT_NEAR(test::totalVolume(m), polygon * (225.0 - 1.0) * (b.hi.z - b.lo.z), 1e-8 * 3000);
}

TEST(GridMesh, HasEveryElementTypeInCfdLikeProportions) {
  const GridMesh g = smallGrid();
  const double total = double(g.elements());
  const double tets = g.elementsOfType(CellType::Tet) / total;
  const double layer =
      (g.elementsOfType(CellType::Wedge) + g.elementsOfType(CellType::Hex)) / total;
  EXPECT_GT(tets, 0.6);
  EXPECT_GT(layer, 0.05);
  EXPECT_GT(g.elementsOfType(CellType::Pyramid), 0u);
  EXPECT_GT(g.elementsOfType(CellType::Hex), 0u);
  EXPECT_GT(g.elementsOfType(CellType::Wedge), g.elementsOfType(CellType::Hex));
}

TEST(GridMesh, ElementCountIsWithinAFewPercentOfTheTargetAtEverySize) {
  for (uint64_t target :
       {10000ull, 100000ull, 1000000ull, 20000000ull, 128000000ull, 1000000000ull}) {
    const GridMesh g({target, 0, 1});
    EXPECT_NEAR(double(g.elements()) / double(target), 1.0, 0.06) << target;
    EXPECT_LE(g.points(), 0xFFFFFFFFull);
    // Default clusters: at least 8, about 4 M elements each.
    EXPECT_EQ(g.clusters(), int(std::max<uint64_t>(8, (g.elements() + 3999999) / 4000000)));
  }
}

TEST(GridMesh, ClustersInterlockAndOneIsNestedInAnother) {
  // A nested ball needs a few cells across inside its host: many clusters need a finer grid.
  for (auto [elements, clusters] :
       {std::pair{2000000ull, 8}, {2000000ull, 40}, {20000000ull, 130}}) {
    const GridMesh g({elements, clusters, 1});
    ASSERT_EQ(g.clusters(), clusters);
    ASSERT_GE(g.nestedCluster(), 0) << clusters;
    const ClusterShapeReport r = clusterShapes(g, 8, 7);
    EXPECT_TRUE(r.nestedEnclosed) << clusters;
    EXPECT_GE(r.fewestMostCrossings, 4) << clusters;
    EXPECT_GT(r.meanCrossings, 2.0) << clusters;
  }
}

TEST(GridMesh, EveryCellBelongsToTheOnePieceOfItsCluster) {
  const GridMesh g = smallGrid(12, 1);
  uint64_t sum = 0;
  for (int k = 0; k < g.clusters(); ++k) sum += g.piece(k).numCells();
  EXPECT_EQ(sum, g.elements());
}

TEST(GridMesh, RefusesSizesItCannotMake) {
  EXPECT_THROW(GridMesh({9999, 0, 1}), Error);
  EXPECT_THROW(GridMesh({3000000000ull, 0, 1}), Error);
  EXPECT_THROW(GridMesh({100000, -1, 1}), Error);
  EXPECT_THROW(GridMesh({100000, 0, 0}), Error);
  std::string message;
  try {
    GridMesh({5000, 0, 1});
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("--elements"), std::string::npos) << message;
}

TEST(PvtuPieceWriter, PiecesWrittenOneByOneReadBackAsTheMesh) {
  const GridMesh g = smallGrid(6, 2);
  const fs::path dir = fs::temp_directory_path() / "sm_grid_pieces";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "grid.pvtu").string();
  {
    mesh::UnstructuredMesh layout;
    addAnalyticFields(layout, g.steps(), g.bounds(), 1);
    io::WriteOptions options;
    options.compress = false;
    io::PvtuPieceWriter writer(path, uint64_t(g.clusters()), layout, options);
    for (int k = g.clusters() - 1; k >= 0; --k) writer.write(uint64_t(k), g.piece(k));
    EXPECT_FALSE(fs::exists(path));  // the index comes last
    writer.finish();
  }
  const mesh::UnstructuredMesh m = io::readMesh(path);
  EXPECT_EQ(m.numCells(), g.elements());
  EXPECT_EQ(m.numPoints(), g.points());
  EXPECT_EQ(m.numClusters(), g.clusters());
  ASSERT_NE(m.findField("density"), nullptr);
  EXPECT_EQ(m.findField("density")->numSteps(), 2u);
  fs::remove_all(dir);
}

TEST(PvtuPieceWriter, AnUnfinishedWriterLeavesNothing) {
  const fs::path dir = fs::temp_directory_path() / "sm_grid_unfinished";
  fs::remove_all(dir);
  fs::create_directories(dir);
  {
    const GridMesh g = smallGrid(4, 1);
    io::PvtuPieceWriter writer((dir / "grid.pvtu").string(), 4, g.piece(0));
    writer.write(0, g.piece(0));
    writer.write(1, g.piece(1));
  }  // a failure before finish()
  EXPECT_FALSE(fs::exists(dir / "grid.pvtu"));
  EXPECT_FALSE(fs::exists(dir / "grid"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sm::gen
