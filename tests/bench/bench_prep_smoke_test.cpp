// `shellmarch bench prep` on a tiny mesh: it runs, prints its table and writes the promised JSON.
#include <gtest/gtest.h>

#include "bench_smoke_util.h"
#include "support/test_support.h"

namespace sm::test {
namespace {

TEST(BenchPrep, TinyMeshWritesPromisedJson) {
  const std::string dir = outputDir("bench_prep");
  const std::string mesh = writeTinyMesh(dir);
  const std::string json = dir + "/prep.json";
  std::string log;
  ASSERT_EQ(runTool({"bench", "prep", "--mesh", mesh, "--runs", "2", "--work-dir", dir + "/work",
                     "--json", json},
                    dir, "prep", log),
            0)
      << log;
  EXPECT_NE(log.find("conn + shell + compaction"), std::string::npos) << log;
  nlohmann::json j = readJson(json);
  ASSERT_FALSE(j.is_discarded()) << json;
  std::vector<std::string> keys = {"machine.cpu",
                                   "machine.logical_cores",
                                   "machine.load_average",
                                   "options.threads",
                                   "targets.conn_shell_compaction_elements_per_second",
                                   "targets.peak_over_prepared",
                                   "meshes.0.elements",
                                   "meshes.0.conn_shell_compaction.elements_per_second",
                                   "meshes.0.memory_peak.prepared_bytes",
                                   "meshes.0.memory_peak.peak_bytes",
                                   "meshes.0.memory_peak.ratio_peak_above_start",
                                   "meshes.0.compaction_savings",
                                   "meshes.0.targets.rate_met",
                                   "meshes.0.targets.memory_met",
                                   "meshes.0.vtk.available"};
  for (const char* stage : {"load", "vertex_order", "connectivity", "shell", "compaction"})
    for (const char* k : {"seconds", "elements_per_second"})
      keys.push_back(std::string("meshes.0.stages.") + stage + "." + k);
  EXPECT_EQ(missingKeys(j, keys), std::vector<std::string>{});
  EXPECT_EQ(j["meshes"][0]["elements"].get<uint64_t>(), 5u * 6 * 6 * 6);
  EXPECT_GT(j["meshes"][0]["memory_peak"]["peak_bytes"].get<uint64_t>(), 0u);
  if (vtkAvailable()) {
    ASSERT_TRUE(j["meshes"][0]["vtk"]["available"].get<bool>()) << j["meshes"][0]["vtk"].dump();
    EXPECT_EQ(missingKeys(j["meshes"][0]["vtk"], {"read_seconds", "weld_seconds", "surface_seconds",
                                                  "geometry_seconds", "peak_rss_bytes", "cells"}),
              std::vector<std::string>{});
    // The welded surface is the cube's: 6 faces of 6 x 6 cells, two triangles each.
    EXPECT_EQ(j["meshes"][0]["vtk"]["surface_polygons"].get<uint64_t>(), 6u * 36 * 2);
    EXPECT_EQ(j["meshes"][0]["shell_triangles"].get<uint64_t>(), 6u * 36 * 2);
  }
}

}  // namespace
}  // namespace sm::test
