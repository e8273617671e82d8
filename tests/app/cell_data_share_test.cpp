// Cell data averaged onto the points rank by rank (app::cellDataToPointsOverRanks) against the
// same average over the whole data set, its pieces joined by the weld as a one-rank read joins
// them (io::weldPieces, then mesh::cellFieldsToPoints). In-process ranks; parts that interlock
// (elements dealt at random, so ranks meet at faces, edges and single points), a baffle (points
// duplicated inside a piece) across rank borders, unused copies listed before used ones, ranks
// without pieces, and ranks that disagree.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include "border/border_exchange.h"
#include "comm/local_communicator.h"
#include "comm/reductions.h"
#include "common/error.h"
#include "gen/generate.h"
#include "io_core/weld.h"
#include "partition/partition.h"
#include "pipeline/cell_data_share.h"
#include "pipeline/rank_share.h"
#include "support/test_meshes.h"
#include "support/test_support.h"

namespace sm::app {
namespace {

using mesh::CellField;
using mesh::UnstructuredMesh;

size_t cellsOf(const UnstructuredMesh& m, int t) {
  return m.cells[t].size() / mesh::numVerts(mesh::kAllCellTypes[t]);
}

// Cell values from the cell's centroid: 'pressure' with `steps` steps and 'density' with one.
void addCellFields(UnstructuredMesh& m, int steps) {
  for (int f = 0; f < 2; ++f) {
    CellField cf{f == 0 ? "pressure" : "density", {}};
    for (int s = 0; s < (f == 0 ? steps : 1); ++s) {
      auto& perType = cf.steps.emplace_back();
      for (int t = 0; t < mesh::kNumCellTypes; ++t)
        for (size_t e = 0; e < cellsOf(m, t); ++e) {
          const glm::dvec3 c = test::cellCentroid(m, t, e);
          perType[t].push_back(float(std::sin(3 * c.x + s) * c.y + (f + 1) * c.z * c.z));
        }
    }
    m.cellFields.push_back(std::move(cf));
  }
}

// Elements dealt to `parts` clusters by a hash of their index.
void dealClusters(UnstructuredMesh& m, int parts) {
  for (int t = 0; t < mesh::kNumCellTypes; ++t)
    for (size_t e = 0; e < m.clusters[t].size(); ++e) {
      const uint64_t i = e + 7919u * uint64_t(t);
      m.clusters[t][e] = int32_t(((i * 0x9E3779B97F4A7C15ull) >> 40) % uint64_t(parts));
    }
}

// Cluster c of `whole` as a piece of a .pvtu: its own points, in their order, and its cell data.
std::vector<UnstructuredMesh> piecesOf(const UnstructuredMesh& whole, int parts, int steps) {
  std::vector<UnstructuredMesh> pieces;
  for (int c = 0; c < parts; ++c) {
    pieces.push_back(partition::extractClustersWithPointMap(whole, {c}).mesh);
    pieces.back().source = "piece " + std::to_string(c);
    addCellFields(pieces.back(), steps);
  }
  return pieces;
}

// A copy of point p, used by no cell, put first in the piece.
void prependUnusedCopy(UnstructuredMesh& piece, uint32_t p) {
  piece.points.insert(piece.points.begin(), piece.points[p]);
  for (auto& ids : piece.cells)
    for (uint32_t& v : ids) ++v;
}

// Rank r holds pieces r, r + ranks, ...: welded as readMesh welds the pieces a rank reads.
UnstructuredMesh shareOf(const std::vector<UnstructuredMesh>& pieces, int rank, int ranks,
                         std::vector<size_t>& held) {
  std::vector<UnstructuredMesh> mine;
  for (size_t c = size_t(rank); c < pieces.size(); c += size_t(ranks)) {
    mine.push_back(pieces[c]);
    held.push_back(c);
  }
  if (mine.empty()) {  // as a rank with no pieces: nothing but the name
    UnstructuredMesh m;
    m.source = "data set";
    return m;
  }
  return io::weldPieces("data set", std::move(mine));
}

// Every corner of every cell a rank holds has the value the welded whole gives that corner.
void expectSameAsWhole(const std::vector<UnstructuredMesh>& pieces, int ranks) {
  UnstructuredMesh whole = io::weldPieces("data set", pieces);
  mesh::cellFieldsToPoints(whole);
  comm::runLocalRanks(ranks, [&](comm::Communicator& c) {
    comm::Communicator& comm = c;
    std::vector<size_t> held;
    UnstructuredMesh m = shareOf(pieces, c.rank(), ranks, held);
    cellDataToPointsOverRanks(m, !held.empty(), "its pieces", comm);
    EXPECT_TRUE(m.cellFields.empty());
    if (held.empty()) return;
    ASSERT_EQ(m.fields.size(), 2u);
    uint64_t compared = 0, exact = 0;
    for (int t = 0; t < mesh::kNumCellTypes; ++t) {
      const uint32_t nv = mesh::numVerts(mesh::kAllCellTypes[t]);
      size_t mine = 0;  // cells are joined type by type, piece after piece
      for (size_t h : held) {
        size_t inWhole = 0;
        for (size_t k = 0; k < h; ++k) inWhole += cellsOf(pieces[k], t);
        for (size_t e = 0; e < cellsOf(pieces[h], t); ++e, ++mine, ++inWhole)
          for (uint32_t v = 0; v < nv; ++v)
            for (size_t f = 0; f < 2; ++f)
              for (size_t s = 0; s < m.fields[f].numSteps(); ++s) {
                const float want = whole.fields[f].steps[s][whole.cells[t][inWhole * nv + v]];
                const float got = m.fields[f].steps[s][m.cells[t][mine * nv + v]];
                ASSERT_NEAR(got, want, 1e-6 * (1 + std::abs(want)))
                    << "rank " << c.rank() << " piece " << h << " type " << t << " cell " << e;
                ++compared;
                exact += got == want;
              }
      }
    }
    // Only the order of summation differs from the whole's: nearly every value is the same.
    EXPECT_GT(compared, 0u);
    EXPECT_GT(exact, compared * 8 / 10);
  });
}

void expectInterlockedSameAsWhole(gen::CubeSplit split, int parts, int ranks, int steps = 3) {
  UnstructuredMesh whole = gen::cube(split, 5);
  dealClusters(whole, parts);
  expectSameAsWhole(piecesOf(whole, parts, steps), ranks);
}

TEST(BorderExchange, TwoHalvesShareTheirMiddlePlane) {
  UnstructuredMesh whole = gen::cube(gen::CubeSplit::Hex, 4);
  for (size_t e = 0; e < whole.clusters[3].size(); ++e)
    whole.clusters[3][e] = test::cellCentroid(whole, 3, e).x < 0.5 ? 0 : 1;
  comm::runLocalRanks(2, [&](comm::Communicator& c) {
    comm::Communicator& comm = c;
    UnstructuredMesh m = partition::extractClustersWithPointMap(whole, {c.rank()}).mesh;
    border::BorderExchange border(m, comm);
    EXPECT_EQ(border.sharedPoints(), 25u);  // the 5 x 5 points of the plane x = 0.5
    // Two columns: ones, and the rank's number plus one.
    std::vector<std::vector<double>> columns{std::vector<double>(m.numPoints(), 1.0),
                                             std::vector<double>(m.numPoints(), c.rank() + 1.0)};
    border.addOtherRanks(columns, comm);
    for (size_t p = 0; p < m.numPoints(); ++p) {
      const bool shared = m.points[p].x == 0.5;
      EXPECT_EQ(columns[0][p], shared ? 2.0 : 1.0) << p;
      EXPECT_EQ(columns[1][p], shared ? 3.0 : c.rank() + 1.0) << p;
    }
  });
}

TEST(BorderExchange, InterlockedTetrahedraAverageAsTheWholeMesh) {
  expectInterlockedSameAsWhole(gen::CubeSplit::Tets5, 3, 4);  // rank 3 holds nothing
}

TEST(BorderExchange, InterlockedPyramidsWedgesAndHexahedraAverageAsTheWholeMesh) {
  expectInterlockedSameAsWhole(gen::CubeSplit::Pyramids, 3, 3);
  expectInterlockedSameAsWhole(gen::CubeSplit::Wedges, 4, 2);  // two pieces per rank
  expectInterlockedSameAsWhole(gen::CubeSplit::Hex, 4, 4);
}

TEST(BorderExchange, ManyStepsGoInSeveralRounds) {
  // 1 + 20 + 1 columns: two rounds of at most 16; rank 3 holds nothing and sends zeros.
  expectInterlockedSameAsWhole(gen::CubeSplit::Tets5, 3, 4, 20);
}

TEST(BorderExchange, OneRankIsTheWholeMesh) {
  expectInterlockedSameAsWhole(gen::CubeSplit::Tets6, 2, 1);
}

// A baffle at z = 0.5: the cells above it use copies of the points there, so a piece with cells on
// both sides holds two points at each position of the plane; slabs along x put the plane across
// every rank border. Some pieces also list an unused copy of a shared point before the used one.
TEST(BorderExchange, CopiesOfAPointPairUpAsTheWeldPairsThem) {
  UnstructuredMesh whole = gen::cube(gen::CubeSplit::Hex, 6);
  std::vector<uint32_t> copyOf(whole.numPoints(), ~0u);
  for (size_t e = 0; e < cellsOf(whole, 3); ++e) {
    whole.clusters[3][e] = std::min(2, int(test::cellCentroid(whole, 3, e).x * 3));
    if (test::cellCentroid(whole, 3, e).z < 0.5) continue;
    for (uint32_t k = 0; k < 8; ++k) {
      uint32_t& v = whole.cells[3][e * 8 + k];
      if (whole.points[v].z != 0.5) continue;
      if (copyOf[v] == ~0u) {
        copyOf[v] = uint32_t(whole.points.size());
        whole.points.push_back(whole.points[v]);
      }
      v = copyOf[v];
    }
  }
  std::vector<UnstructuredMesh> pieces = piecesOf(whole, 3, 2);
  for (size_t c = 1; c < pieces.size(); ++c) {
    for (uint32_t p = 0; p < pieces[c].numPoints(); ++p)
      if (pieces[c].points[p].x == double(c) / 3 && pieces[c].points[p].y == 0.5) {
        prependUnusedCopy(pieces[c], p);
        break;
      }
  }
  expectSameAsWhole(pieces, 3);
}

void expectAllRanksFail(const std::vector<UnstructuredMesh>& pieces, int ranks,
                        const std::string& want) {
  try {
    comm::runLocalRanks(ranks, [&](comm::Communicator& c) {
      comm::Communicator& comm = c;
      std::vector<size_t> held;
      UnstructuredMesh m = shareOf(pieces, c.rank(), ranks, held);
      try {
        cellDataToPointsOverRanks(m, !held.empty(), concat("piece ", held.at(0)), comm);
        ADD_FAILURE() << "rank " << c.rank() << ": no error";
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << e.what();
      }
      throw Error("all failed");
    });
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "all failed");
  }
}

TEST(BorderExchange, RanksWhoseCellDataDiffersAllFailNamingBoth) {
  UnstructuredMesh whole = gen::cube(gen::CubeSplit::Hex, 3);
  dealClusters(whole, 3);
  std::vector<UnstructuredMesh> pieces = piecesOf(whole, 3, 3);
  pieces[1].cellFields[0].steps.pop_back();  // piece 1: 2 steps of 'pressure', the others 3
  expectAllRanksFail(pieces, 3,
                     "the pieces do not hold the same cell data: rank 0 (piece 0) has 'pressure' "
                     "with 3 steps, 'density' with 1 step; rank 1 (piece 1) has 'pressure' with 2");
}

TEST(BorderExchange, ARankWhosePiecesHoldNoCellDataFailsWithTheOthers) {
  UnstructuredMesh whole = gen::cube(gen::CubeSplit::Tets5, 3);
  dealClusters(whole, 2);
  std::vector<UnstructuredMesh> pieces = piecesOf(whole, 2, 1);
  pieces[1].cellFields.clear();  // as a piece whose array of that name is point data
  expectAllRanksFail(pieces, 2, "rank 1 (piece 1) has no cell data asked for");
}

// Cell data 'q' of `path` on one rank, streamed (render's and view's way) and read whole, against
// want(point) at every point; the file's three polyhedra split.
void expectPolyhedraQ(const std::string& path, const std::function<float(glm::dvec3)>& want) {
  for (bool stream : {true, false}) {
    SCOPED_TRACE(stream ? "streamed" : "whole");
    comm::runLocalRanks(1, [&](comm::Communicator& c) {
      comm::Communicator& comm = c;
      ShareOptions o;
      o.read.fields = {"q"};
      o.streamSteps = stream;
      const RankShare s = loadRankShare(path, o, comm);
      ASSERT_EQ(s.mesh.fields.size(), 1u);
      EXPECT_EQ(s.mesh.skipped.polyhedraSplit, 3u);
      for (size_t p = 0; p < s.mesh.numPoints(); ++p) {
        const glm::dvec3 x = s.mesh.points[p];
        EXPECT_FLOAT_EQ(s.mesh.fields[0].steps[0][p], want(x)) << x.x << " " << x.y << " " << x.z;
      }
    });
  }
}

// q of tests/io/data/polyhedra.vtu at point x: two cubes (q = 1, 2) sharing the face x = 1, and a
// hexagonal prism (q = 3) beyond x = 2.5.
float polyhedraQ(glm::dvec3 x) {
  return x.x > 2.5 ? 3.0f : x.x == 1.0 ? 1.5f : x.x < 1.0 ? 1.0f : 2.0f;
}

// Cell data of polyhedra, streamed (render's and view's way) and read whole: each polyhedron
// counts once at each of its points however many of its tetrahedra meet there (the two cubes of
// tests/io/data/polyhedra.vtu share the face x = 1: q there is (1 + 2) / 2).
TEST(PolyhedraCellData, EachPolyhedronCountsOnceAtAPoint) {
  expectPolyhedraQ(std::string(SHELLMARCH_IO_TEST_DATA) + "/polyhedra.vtu", polyhedraQ);
}

// The same polyhedra as one piece of a .pvtu whose other piece holds a hexahedron (q = 4) on top
// of the second cube (sharing its face z = 1, and an edge with the first cube): only the first
// piece has polyhedra, so only it records where its elements came from, and the join must still
// count each polyhedron once at a point (it counted every tetrahedron when origins were kept only
// if every piece had them).
TEST(PolyhedraCellData, APieceWithoutPolyhedraKeepsTheCountRight) {
  const std::string dir = test::outputDir("PolyhedraCellData.Pieces");
  std::filesystem::copy_file(std::string(SHELLMARCH_IO_TEST_DATA) + "/polyhedra.vtu",
                             dir + "/poly.vtu", std::filesystem::copy_options::overwrite_existing);
  std::ofstream(dir + "/hex.vtu")
      << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\"><UnstructuredGrid>"
         "<Piece NumberOfPoints=\"8\" NumberOfCells=\"1\"><CellData>"
         "<DataArray type=\"Float32\" Name=\"q\" format=\"ascii\">4</DataArray></CellData>"
         "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">"
         "1 0 1 2 0 1 2 1 1 1 1 1 1 0 2 2 0 2 2 1 2 1 1 2</DataArray></Points><Cells>"
         "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 2 3 4 5 6 7"
         "</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">8</DataArray>"
         "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">12</DataArray></Cells>"
         "</Piece></UnstructuredGrid></VTKFile>\n";
  std::ofstream(dir + "/both.pvtu")
      << "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\"><PUnstructuredGrid GhostLevel=\"0\">"
         "<PCellData><PDataArray type=\"Float32\" Name=\"q\"/></PCellData>"
         "<PPoints><PDataArray type=\"Float64\" NumberOfComponents=\"3\"/></PPoints>"
         "<Piece Source=\"poly.vtu\"/><Piece Source=\"hex.vtu\"/></PUnstructuredGrid></VTKFile>\n";
  expectPolyhedraQ(dir + "/both.pvtu", [](glm::dvec3 x) {
    if (x.z == 2.0) return 4.0f;
    if (x.z == 1.0 && x.x == 2.0) return (2.0f + 4.0f) / 2.0f;
    if (x.z == 1.0 && x.x == 1.0) return (1.0f + 2.0f + 4.0f) / 3.0f;
    return polyhedraQ(x);
  });
}

}  // namespace
}  // namespace sm::app
