// `shellmarch bench features` at 32², one frame per variant: every table's rows are there, the
// log scale's among them, each with its frames and a time; the JSON holds what docs/BENCHMARKS.md
// reports (no timing is asserted).
#include <gtest/gtest.h>

#include <set>

#include "bench_smoke_util.h"
#include "support/test_support.h"

namespace sm::test {
namespace {

TEST(BenchFeatures, EveryVariantIsTimedAndReported) {
  const std::string dir = outputDir("bench_features");
  const std::string json = dir + "/features.json";
  std::string log;
  ASSERT_EQ(runTool({"bench", "features", "--size", "32", "--runs", "1", "--rounds", "1",
                     "--work-dir", dir, "--json", json},
                    dir, "features", log),
            0)
      << log;
  EXPECT_NE(log.find("| log scale"), std::string::npos) << log;
  nlohmann::json j = readJson(json);
  ASSERT_FALSE(j.is_discarded()) << json;
  ASSERT_EQ(missingKeys(j, {"machine.cpu", "device", "size.0", "element_bytes.compacted",
                            "element_bytes.plain", "rows.0.ms"}),
            std::vector<std::string>{});
  std::set<std::string> features;
  for (const nlohmann::json& row : j["rows"]) {
    features.insert(row["feature"].get<std::string>());
    EXPECT_EQ(row["frames"].size(), 1u) << row.dump();
    EXPECT_GT(row["ms"].get<double>(), 0.0) << row.dump();
  }
  for (const char* f : {"element types", "shading", "fixed-step sampling", "XOR compaction",
                        "8-bit fragments", "log scale", "exchange between ranks"})
    EXPECT_TRUE(features.count(f)) << f;
  EXPECT_LT(j["element_bytes"]["compacted"].get<double>(),
            j["element_bytes"]["plain"].get<double>());
}

}  // namespace
}  // namespace sm::test
