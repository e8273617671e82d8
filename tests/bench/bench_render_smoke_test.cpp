// `shellmarch bench render` on a tiny mesh at 32²: it runs (validation on), prints its tables and
// writes the promised JSON, VTK's images compared too when VTK is there.
#include <gtest/gtest.h>

#include "bench_smoke_util.h"
#include "support/test_support.h"

namespace sm::test {
namespace {

// A name listed twice is an option error before anything is measured.
TEST(BenchRender, RepeatedNamesAreOptionErrors) {
  const std::string dir = outputDir("bench_render_options");
  const std::string mesh = writeTinyMesh(dir);
  for (const char* option : {"--integrators", "--pair-integrators", "--references"}) {
    const char* value = std::string(option) == "--references" ? "grid,grid" : "linear,linear";
    std::vector<std::string> args = {"bench", "render",     "--mesh",      mesh,      option,
                                     value,   "--work-dir", dir + "/work", "--no-vtk"};
    if (std::string(option) == "--pair-integrators")
      args.insert(args.end(), {"--integrators", "linear"});
    std::string log;
    EXPECT_NE(runTool(args, dir, "options", log), 0) << log;
    EXPECT_NE(log.find(std::string(option) + ": '" + std::string(value).substr(0, 4)),
              std::string::npos)
        << log;
    EXPECT_NE(log.find("listed twice"), std::string::npos) << log;
  }
}

TEST(BenchRender, TinyMeshWritesPromisedJson) {
  const std::string dir = outputDir("bench_render");
  const std::string mesh = writeTinyMesh(dir);
  const std::string json = dir + "/render.json";
  std::string log;
  ASSERT_EQ(runTool({"bench",
                     "render",
                     "--mesh",
                     mesh,
                     "--sizes",
                     "32,24x16",
                     "--runs",
                     "2",
                     "--vtk-runs",
                     "1",
                     "--integrators",
                     "linear",
                     "--pair-rounds",
                     "2",
                     "--pair-integrators",
                     "linear",
                     "--first-image",
                     "24x16",
                     "--first-image-runs",
                     "1",
                     "--work-dir",
                     dir + "/work",
                     "--json",
                     json},
                    dir, "render", log),
            0)
      << log;
  EXPECT_NE(log.find("M samples/s"), std::string::npos) << log;
  nlohmann::json j = readJson(json);
  ASSERT_FALSE(j.is_discarded()) << json;
  std::vector<std::string> keys = {"machine.cpu",        "device",        "setup.elements",
                                   "setup.load_seconds", "vtk.available", "goals",
                                   "sizes.1.width"};
  for (const char* mode : {"compacted", "plain"})
    for (const char* k : {"cold_first_frame_ms", "warm_ms", "frames_per_second",
                          "samples_per_second", "cache_retraces", "stages_ms.traversal",
                          "stages_ms.scan", "stages_ms.march", "stages_ms.composite"})
      keys.push_back(std::string("sizes.0.shellmarch.") + mode + "." + k);
  for (const char* img :
       {"shellmarch compacted", "shellmarch plain", "reference rounded to 8 bits"})
    for (const char* ref : {"grid", "converged"})
      for (const char* k : {"rmse", "max_abs", "psnr"})
        keys.push_back(std::string("sizes.0.errors.") + img + "." + ref + "." + k);
  for (const char* k :
       {"cold_seconds", "warm_seconds", "startup_cold.context_ms", "startup_warm.first_frame_ms",
        "startup_warm.pipelines_ms", "vtk.available"})
    keys.push_back(std::string("first_image.") + k);
  EXPECT_EQ(missingKeys(j, keys), std::vector<std::string>{});
  // The first image: the cold process compiles every shader; where shaders are kept as shader
  // objects (lavapipe), the warm one takes them all from the shader cache the cold one filled.
  const auto& first = j["first_image"];
  EXPECT_EQ(first["width"].get<int>(), 24);
  EXPECT_EQ(first["startup_cold"]["pipelines_from_cache_rank0"].get<uint64_t>(), 0u);
  if (first["startup_warm"]["shader_objects"].get<bool>())
    EXPECT_EQ(first["startup_warm"]["pipelines_from_cache_rank0"].get<uint64_t>(),
              first["startup_warm"]["pipelines_rank0"].size());
  EXPECT_NE(log.find("first image 24x16"), std::string::npos) << log;
  // shellmarch samples the grid the reference samples: its image is the grid reference's.
  EXPECT_LT(j["sizes"][0]["errors"]["shellmarch compacted"]["grid"]["max_abs"].get<double>(), 0.02);
  EXPECT_EQ(j["sizes"][0]["compacted_vs_plain_max_abs"].get<double>(), 0.0);
  // The default traces each ray once (fused); the stage-split row times traversal and marching
  // apart and gives the same image.
  const auto& size0 = j["sizes"][0];
  EXPECT_TRUE(size0["shellmarch"]["compacted"]["fused"].get<bool>());
  const auto& split = size0["shellmarch"]["compacted_coarser"][0];
  EXPECT_EQ(split["label"].get<std::string>(), "shellmarch compacted stage-split");
  EXPECT_FALSE(split["fused"].get<bool>());
  EXPECT_GT(split["stages_ms"]["march"].get<double>(), 0.0);
  // Both tracers count their shell queries: at least one per segment found.
  for (const auto* run : {&size0["shellmarch"]["compacted"], &split})
    EXPECT_GE((*run)["shell_queries"].get<uint64_t>(), (*run)["segments"].get<uint64_t>()) << *run;
  EXPECT_GT(split["segments"].get<uint64_t>(), 0u);
  EXPECT_EQ(size0["errors"]["shellmarch compacted stage-split"]["grid"]["rmse"].get<double>(),
            size0["errors"]["shellmarch compacted"]["grid"]["rmse"].get<double>());
  EXPECT_NE(log.find("stage-split"), std::string::npos) << log;
  if (vtkAvailable()) {
    ASSERT_TRUE(j["vtk"]["available"].get<bool>()) << j["vtk"].dump();
    EXPECT_GT(first["vtk"]["seconds"].get<double>(), 0.0) << first.dump();
    EXPECT_GT(first["vtk_over_warm"].get<double>(), 0.0) << first.dump();
    EXPECT_EQ(missingKeys(j, {"vtk.sizes.0.integrators.0.warm_ms",
                              "vtk.sizes.0.integrators.0.cold_first_frame_ms",
                              "sizes.0.errors.VTK linear.converged.rmse", "goals.0.speedup",
                              "goals.0.met"}),
              std::vector<std::string>{});
    // Paired rounds: two of them, shellmarch's equal-error run and VTK timed in each, and the
    // goal decided on their median.
    for (const auto& g : j["goals"]) {
      if (g["equal_error_run"].is_null()) continue;
      ASSERT_TRUE(g.contains("paired")) << g.dump();
      EXPECT_FALSE(g.contains("paired_error")) << g.dump();
      const auto& p = g["paired"];
      ASSERT_EQ(p["rounds"].size(), 2u) << p.dump();
      for (const auto& r : p["rounds"]) {
        EXPECT_GT(r["shellmarch_ms"].get<double>(), 0.0);
        EXPECT_GT(r["vtk_ms"].get<double>(), 0.0);
      }
      EXPECT_LE(p["ratio_min"].get<double>(), p["ratio_median"].get<double>());
      EXPECT_LE(p["ratio_median"].get<double>(), p["ratio_max"].get<double>());
      EXPECT_EQ(g["met"].get<bool>(), p["ratio_median"].get<double>() >= 5.0);
    }
    EXPECT_NE(log.find("paired rounds (2, shellmarch then VTK in each)"), std::string::npos) << log;
  }
}

}  // namespace
}  // namespace sm::test
