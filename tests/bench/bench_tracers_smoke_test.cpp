// `shellmarch bench tracers` on a tiny mesh and on an in-memory cube: every tracer the device
// offers is timed, the JSON holds what docs/BENCHMARKS.md promises, and where both tracers ran
// their images are reported identical (they are: the render tests compare them bit for bit).
#include <gtest/gtest.h>

#include "bench_smoke_util.h"
#include "support/test_support.h"

namespace sm::test {
namespace {

void expectReport(const nlohmann::json& j) {
  ASSERT_FALSE(j.is_discarded());
  std::vector<std::string> keys = {"machine.cpu", "device", "elements", "sizes.0.width",
                                   "sizes.0.device_bytes_in_use"};
  for (const char* k : {"tracer", "cold_first_frame_ms", "round_ms", "warm_ms", "trace_ms",
                        "composite_ms", "frames_per_second", "m_element_steps_per_second",
                        "m_pixels_per_second", "elements_x_fps", "lost_rays"})
    keys.push_back(std::string("sizes.0.tracers.0.") + k);
  ASSERT_EQ(missingKeys(j, keys), std::vector<std::string>{});
  const nlohmann::json& size = j["sizes"][0];
  EXPECT_EQ(size["tracers"][0]["round_ms"].size(), 2u);
  EXPECT_EQ(size["tracers"][0]["lost_rays"].get<int>(), 0);
  EXPECT_GT(size["tracers"][0]["m_element_steps_per_second"].get<double>(), 0.0);
  if (size["tracers"].size() == 2) {
    EXPECT_EQ(size["tracers"][1]["tracer"], "pipeline");
    EXPECT_TRUE(size["images_identical"].get<bool>());
    ASSERT_EQ(missingKeys(size, {"pipeline_over_query.median", "pipeline_over_query.min"}),
              std::vector<std::string>{});
  }
}

TEST(BenchTracers, TinyMeshAndAnalyticCubeWritePromisedJson) {
  const std::string dir = outputDir("bench_tracers");
  const std::string mesh = writeTinyMesh(dir);
  std::string log;
  ASSERT_EQ(runTool({"bench", "tracers", "--mesh", mesh, "--sizes", "24", "--rounds", "2", "--runs",
                     "1", "--json", dir + "/mesh.json", "--markdown", dir + "/mesh.md"},
                    dir, "mesh", log),
            0)
      << log;
  EXPECT_NE(log.find("| 24² | query |"), std::string::npos) << log;
  expectReport(readJson(dir + "/mesh.json"));
  ASSERT_EQ(runTool({"bench", "tracers", "--analytic", "cube-tets6", "--cube-n", "3", "--sizes",
                     "24", "--rounds", "2", "--runs", "1", "--tracers", "pipeline", "--json",
                     dir + "/cube.json"},
                    dir, "cube", log),
            0)
      << log;
  const nlohmann::json cube = readJson(dir + "/cube.json");
  expectReport(cube);
  EXPECT_EQ(cube["elements"].get<int>(), 6 * 27);
  EXPECT_EQ(cube["sizes"][0]["tracers"].size(), 1u);
}

}  // namespace
}  // namespace sm::test
