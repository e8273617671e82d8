// Several fields streamed at once, cell data and point data mixed (the viewer's way since it
// browses a file's cell data too): every step of every field, as app::StepSource hands it out, has
// the range it has when every step is loaded with the mesh, on one rank and on ranks that meet at
// interlocked pieces (one rank holding none).
#include <gtest/gtest.h>

#include <cmath>

#include "comm/local_communicator.h"
#include "comm/reductions.h"
#include "gen/generate.h"
#include "io/mesh_io.h"
#include "pipeline/rank_share.h"
#include "pipeline/step_source.h"
#include "support/test_meshes.h"
#include "support/test_support.h"

namespace sm::app {
namespace {

using mesh::UnstructuredMesh;

// Three pieces dealt by a hash of the element (so that they interlock); point field 'temperature'
// with 2 steps, cell data 'pressure' with 3 and 'density' with 1, each step its own values.
UnstructuredMesh meshWithFields() {
  UnstructuredMesh m = gen::cube(gen::CubeSplit::Tets5, 4);
  for (auto& clusters : m.clusters)
    for (size_t e = 0; e < clusters.size(); ++e)
      clusters[e] = int32_t(((e * 0x9E3779B97F4A7C15ull) >> 40) % 3u);
  mesh::Field temperature{"temperature", {}};
  for (int s = 0; s < 2; ++s) {
    auto& v = temperature.steps.emplace_back();
    for (const glm::dvec3& p : m.points) v.push_back(float(p.x + 2 * p.y * p.z + s));
  }
  m.fields = {temperature};
  for (int f = 0; f < 2; ++f) {
    mesh::CellField cf{f == 0 ? "pressure" : "density", {}};
    for (int s = 0; s < (f == 0 ? 3 : 1); ++s) {
      auto& perType = cf.steps.emplace_back();
      for (int t = 0; t < mesh::kNumCellTypes; ++t)
        for (size_t e = 0; e < m.clusters[t].size(); ++e) {
          const glm::dvec3 c = test::cellCentroid(m, t, e);
          perType[t].push_back(float(std::sin(3 * c.x + s) * c.y + (f + 1) * (s + 1) * c.z * c.z));
        }
    }
    m.cellFields.push_back(std::move(cf));
  }
  return m;
}

TEST(StreamedFields, CellAndPointDataStreamAsTheyLoadWhole) {
  const std::string path = test::outputDir("StreamedFields") + "/m.pvtu";
  io::writePvtu(path, meshWithFields());
  const std::vector<std::pair<std::string, uint64_t>> fields = {
      {"temperature", 2}, {"pressure", 3}, {"density", 1}};
  for (int ranks : {1, 4}) {
    SCOPED_TRACE(std::to_string(ranks) + " ranks");
    comm::runLocalRanks(ranks, [&](comm::Communicator& c) {
      comm::Communicator& comm = c;
      ShareOptions o;
      for (const auto& f : fields) o.read.fields.push_back(f.first);
      o.streamSteps = true;
      const RankShare streamed = loadRankShare(path, o, comm);
      o.streamSteps = false;
      const RankShare whole = loadRankShare(path, o, comm);
      ASSERT_TRUE(streamed.stream.has_value());
      ASSERT_FALSE(whole.stream.has_value());
      const StepSource a(path, streamed, comm), b(path, whole, comm);
      EXPECT_FALSE(a.collective("temperature"));
      EXPECT_TRUE(a.collective("pressure"));
      EXPECT_TRUE(a.collective("density"));
      EXPECT_FALSE(b.collective("pressure"));
      const bool holds = c.rank() < 3;  // three pieces: rank 3 of 4 reads none
      for (const auto& [name, steps] : fields) {
        EXPECT_EQ(a.numSteps(name), holds ? steps : 0u) << name;
        EXPECT_EQ(b.numSteps(name), holds ? steps : 0u) << name;
        for (uint64_t s = 0; s < steps; ++s) {
          // Collective for cell data: every rank asks, in the same order.
          const mesh::Range ra = a.range(name, s), rb = b.range(name, s);
          if (!holds) continue;
          EXPECT_NEAR(ra.lo, rb.lo, 1e-6 * std::abs(rb.lo) + 1e-7) << name << " step " << s;
          EXPECT_NEAR(ra.hi, rb.hi, 1e-6 * std::abs(rb.hi) + 1e-7) << name << " step " << s;
          EXPECT_LT(ra.lo, ra.hi) << name << " step " << s;
        }
      }
    });
  }
}

}  // namespace
}  // namespace sm::app
