// `shellmarch bench counts` on a tiny mesh at 24²: every virtual rank's share is rendered, its
// counts dumped and replayed; the JSON holds what docs/BENCHMARKS.md reports, and the replay's
// byte accounting has the known answers of one rank (nothing sent) and of the dump's size.
#include <gtest/gtest.h>

#include <filesystem>

#include "bench_smoke_util.h"
#include "support/test_support.h"

namespace sm::test {
namespace {

TEST(BenchCounts, TinyMeshDumpsAndReplaysRealCounts) {
  const std::string dir = outputDir("bench_counts");
  const std::string mesh = writeTinyMesh(dir);
  const std::string json = dir + "/counts.json";
  std::string log;
  ASSERT_EQ(runTool({"bench", "counts", "--mesh", mesh, "--ranks", "1,3", "--sizes", "24",
                     "--field", "vortex", "--dump-dir", dir + "/dumps", "--json", json},
                    dir, "counts", log),
            0)
      << log;
  EXPECT_NE(log.find("render imbal"), std::string::npos) << log;
  nlohmann::json j = readJson(json);
  ASSERT_FALSE(j.is_discarded()) << json;
  std::vector<std::string> keys = {"machine.cpu", "device", "rows.1.ranks"};
  for (const char* k :
       {"fragments", "counter_bits", "count_bytes_sent.max", "fragment_bytes_sent_float.mean",
        "fragment_bytes_sent_rgba8.max", "render_imbalance", "composite_imbalance",
        "composite_imbalance_ranges", "dump"})
    keys.push_back(std::string("rows.1.") + k);
  ASSERT_EQ(missingKeys(j, keys), std::vector<std::string>{});
  const nlohmann::json& one = j["rows"][0];
  const nlohmann::json& three = j["rows"][1];
  EXPECT_EQ(one["ranks"].get<int>(), 1);
  EXPECT_GT(one["fragments"].get<double>(), 0.0);
  EXPECT_EQ(one["count_bytes_sent"]["max"].get<double>(), 0.0) << "one rank sends nothing";
  EXPECT_EQ(one["fragment_bytes_sent_float"]["max"].get<double>(), 0.0);
  EXPECT_EQ(three["ranks"].get<int>(), 3);
  EXPECT_GT(three["fragment_bytes_sent_float"]["mean"].get<double>(), 0.0);
  EXPECT_GE(three["render_imbalance"].get<double>(), 1.0);
  // The tiny mesh covers the middle rows of the image: contiguous ranges give that band to one
  // rank, interleaved ownership to all three alike (1.93 and 1.01 when written).
  EXPECT_LT(three["composite_imbalance"].get<double>(), 1.1);
  EXPECT_GT(three["composite_imbalance_ranges"].get<double>(), 1.5);
  // 8 bytes of magic, 4 header words, then one count per pixel and rank.
  const std::string dump = three["dump"].get<std::string>();
  EXPECT_EQ(std::filesystem::file_size(dump), 24u + 3u * 24u * 24u * 4u);
  EXPECT_FALSE(std::filesystem::exists(dump + ".part"));
}

}  // namespace
}  // namespace sm::test
