// Cell data averaged onto the points rank by rank (app::cellDataToPointsOverRanks) against the
// same average over the whole mesh, on in-process ranks whose parts interlock: elements are dealt
// to ranks at random, so ranks meet at faces, edges and single vertices, and some points are
// shared by every rank.
#include <gtest/gtest.h>

#include <cmath>

#include "app/border_exchange.h"
#include "app/comm_collectives.h"
#include "common/error.h"
#include "compositor/local_communicator.h"
#include "gen/generate.h"
#include "partition/partition.h"

namespace sm::app {
namespace {

using mesh::CellField;
using mesh::UnstructuredMesh;

glm::dvec3 centroid(const UnstructuredMesh& m, int t, size_t e) {
  const uint32_t nv = mesh::numVerts(mesh::kAllCellTypes[t]);
  glm::dvec3 c(0.0);
  for (uint32_t k = 0; k < nv; ++k) c += m.points[m.cells[t][e * nv + k]];
  return c / double(nv);
}

// Cell values from the cell's centroid, so that a part computes the same values as the whole.
void addCellFields(UnstructuredMesh& m, int steps) {
  for (int f = 0; f < 2; ++f) {
    CellField cf{f == 0 ? "pressure" : "density", {}};
    for (int s = 0; s < (f == 0 ? steps : 1); ++s) {
      auto& perType = cf.steps.emplace_back();
      for (int t = 0; t < mesh::kNumCellTypes; ++t)
        for (size_t e = 0; e < m.cells[t].size() / mesh::numVerts(mesh::kAllCellTypes[t]); ++e) {
          const glm::dvec3 c = centroid(m, t, e);
          perType[t].push_back(float(std::sin(3 * c.x + s) * c.y + (f + 1) * c.z * c.z));
        }
    }
    m.cellFields.push_back(std::move(cf));
  }
}

// Elements dealt to `parts` clusters by a hash of their index.
void dealClusters(UnstructuredMesh& m, int parts) {
  for (int t = 0; t < mesh::kNumCellTypes; ++t)
    for (auto& c : m.clusters[t]) {
      const uint64_t i = uint64_t(&c - m.clusters[t].data()) + 7919u * uint64_t(t);
      c = int32_t(((i * 0x9E3779B97F4A7C15ull) >> 40) % uint64_t(parts));
    }
}

// Rank r holds cluster r (none when r >= parts), with the cell fields its own elements give.
UnstructuredMesh shareOf(const UnstructuredMesh& whole, int rank, int parts,
                         std::vector<uint32_t>& original, int steps) {
  UnstructuredMesh m;
  m.source = "interlocked";
  if (rank >= parts) return m;  // as a rank with no pieces: nothing but the name
  partition::ExtractedClusters ex = partition::extractClustersWithPointMap(whole, {rank});
  original = std::move(ex.originalPoint);
  m = std::move(ex.mesh);
  addCellFields(m, steps);
  return m;
}

void expectSameAsWhole(gen::CubeSplit split, int parts, int ranks) {
  UnstructuredMesh whole = gen::cube(split, 5);
  whole.source = "interlocked";
  dealClusters(whole, parts);
  UnstructuredMesh averaged = whole;
  addCellFields(averaged, 3);
  mesh::cellFieldsToPoints(averaged);
  comp::runLocalRanks(ranks, [&](comp::Communicator& c) {
    CommCollectives coll(c);
    std::vector<uint32_t> original;
    UnstructuredMesh m = shareOf(whole, c.rank(), parts, original, 3);
    cellDataToPointsOverRanks(m, coll);
    EXPECT_TRUE(m.cellFields.empty());
    if (c.rank() >= parts) return;
    ASSERT_EQ(m.fields.size(), 2u);
    uint64_t exact = 0;
    for (size_t f = 0; f < 2; ++f) {
      ASSERT_EQ(m.fields[f].name, averaged.fields[f].name);
      ASSERT_EQ(m.fields[f].numSteps(), averaged.fields[f].numSteps());
      for (size_t s = 0; s < m.fields[f].numSteps(); ++s)
        for (size_t p = 0; p < m.numPoints(); ++p) {
          const float want = averaged.fields[f].steps[s][original[p]];
          const float got = m.fields[f].steps[s][p];
          ASSERT_NEAR(got, want, 1e-6 * (1 + std::abs(want)))
              << "rank " << c.rank() << " point " << p << " field " << f << " step " << s;
          exact += got == want;
        }
    }
    // Only the order of summation differs from the whole mesh's: nearly every value is the same.
    EXPECT_GT(exact, 9 * m.numPoints() * 4 / 10);
  });
}

TEST(BorderExchange, TwoHalvesShareTheirMiddlePlane) {
  UnstructuredMesh whole = gen::cube(gen::CubeSplit::Hex, 4);
  for (size_t e = 0; e < whole.clusters[3].size(); ++e)
    whole.clusters[3][e] = centroid(whole, 3, e).x < 0.5 ? 0 : 1;
  comp::runLocalRanks(2, [&](comp::Communicator& c) {
    CommCollectives coll(c);
    UnstructuredMesh m = partition::extractClustersWithPointMap(whole, {c.rank()}).mesh;
    BorderExchange border(m, coll);
    EXPECT_EQ(border.sharedPoints(), 25u);  // the 5 x 5 points of the plane x = 0.5
    std::vector<double> ones(m.numPoints(), 1.0);
    border.addOtherRanks(ones, coll);
    uint64_t twos = 0;
    for (size_t p = 0; p < m.numPoints(); ++p) {
      EXPECT_EQ(ones[p], m.points[p].x == 0.5 ? 2.0 : 1.0) << p;
      twos += ones[p] == 2.0;
    }
    EXPECT_EQ(twos, 25u);
  });
}

TEST(BorderExchange, InterlockedTetrahedraAverageAsTheWholeMesh) {
  expectSameAsWhole(gen::CubeSplit::Tets5, 3, 4);  // rank 3 holds nothing
}

TEST(BorderExchange, InterlockedPyramidsWedgesAndHexahedraAverageAsTheWholeMesh) {
  expectSameAsWhole(gen::CubeSplit::Pyramids, 3, 3);
  expectSameAsWhole(gen::CubeSplit::Wedges, 2, 2);
  expectSameAsWhole(gen::CubeSplit::Hex, 4, 4);
}

TEST(BorderExchange, OneRankIsTheWholeMesh) {
  expectSameAsWhole(gen::CubeSplit::Tets6, 1, 1);
}

TEST(BorderExchange, RanksWhoseCellDataDiffersAllFail) {
  UnstructuredMesh whole = gen::cube(gen::CubeSplit::Hex, 3);
  dealClusters(whole, 3);
  try {
    comp::runLocalRanks(3, [&](comp::Communicator& c) {
      CommCollectives coll(c);
      std::vector<uint32_t> original;
      // Rank 1's pieces have 2 steps of 'pressure', the others 3.
      UnstructuredMesh m = shareOf(whole, c.rank(), 3, original, c.rank() == 1 ? 2 : 3);
      EXPECT_THROW(cellDataToPointsOverRanks(m, coll), Error);
      throw Error("all failed");
    });
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "all failed");
  }
}

}  // namespace
}  // namespace sm::app
