// Paired rounds of `shellmarch bench render` with made-up frame times: which goals are paired, in
// what order the renderers run, the ratios and the goal decided on their median.
#include "bench/paired_rounds.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "common/error.h"

namespace sm::app::bench {
namespace {

nlohmann::json goal(int width, const char* integrator, const char* run, double speedup) {
  return {{"width", width},
          {"height", width},
          {"vtk_integrator", integrator},
          {"equal_error_run", run ? nlohmann::json(run) : nlohmann::json()},
          {"speedup", speedup},
          {"met", speedup >= 5.0}};
}

nlohmann::json threeGoals() {
  nlohmann::json r;
  r["goals"] = {goal(512, "preintegration", "shellmarch compacted dt×5", 3.0),
                goal(512, "linear", "shellmarch element-exact", 17.0),
                goal(1024, "preintegration", nullptr, 0.0)};
  return r;
}

// shellmarch takes 100 ms per frame; VTK's times follow `vtkMs`, one per round.
struct Fake {
  std::vector<double> vtkMs;
  std::string calls;
  int vtkCalls = 0;
  int failAt = -1;            // VTK fails in this round (0-based)
  bool foreignError = false;  // ... with a std::runtime_error instead of an Error
  PairedRoundHooks hooks() {
    PairedRoundHooks h;
    h.shellmarch = [this](const nlohmann::json& g) {
      // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on "S" + string.
      calls += 'S';
      calls += std::to_string(g["width"].get<int>());
      calls += ' ';
      return FrameTime{100.0, 150.0};
    };
    h.vtk = [this](const std::vector<const nlohmann::json*>& goals) {
      calls += "V ";
      if (vtkCalls == failAt && foreignError) throw std::runtime_error("VTK's JSON is truncated");
      if (vtkCalls == failAt) throw Error("VTK crashed");
      double ms = vtkMs[size_t(vtkCalls++)];
      return std::vector<FrameTime>(goals.size(), FrameTime{ms, 2 * ms});
    };
    return h;
  }
};

TEST(PairedRounds, TakeTurnsAndDecideOnTheMedian) {
  nlohmann::json r = threeGoals();
  Fake f{{400.0, 650.0, 520.0}};
  runPairedRounds(r, 3, {"preintegration"}, f.hooks(), 5.0);
  // Only the pre-integrated goal with an equal-error run is paired; shellmarch, then VTK, per
  // round.
  EXPECT_EQ(f.calls, "S512 V S512 V S512 V ");
  const auto& g = r["goals"][0];
  ASSERT_TRUE(g.contains("paired"));
  EXPECT_FALSE(r["goals"][1].contains("paired"));
  EXPECT_FALSE(r["goals"][2].contains("paired"));
  const auto& p = g["paired"];
  ASSERT_EQ(p["rounds"].size(), 3u);
  EXPECT_DOUBLE_EQ(p["rounds"][1]["ratio"].get<double>(), 6.5);
  EXPECT_DOUBLE_EQ(p["rounds"][1]["ratio_cpu"].get<double>(), 1300.0 / 150.0);
  EXPECT_DOUBLE_EQ(p["ratio_median"].get<double>(), 5.2);
  EXPECT_DOUBLE_EQ(p["ratio_min"].get<double>(), 4.0);
  EXPECT_DOUBLE_EQ(p["ratio_max"].get<double>(), 6.5);
  // The single run said 3x (not met); the paired median, 5.2x, decides.
  EXPECT_TRUE(g["met"].get<bool>());
  EXPECT_DOUBLE_EQ(g["speedup"].get<double>(), 3.0);
  EXPECT_EQ(
      pairedSummary(g),
      "paired rounds (3, shellmarch then VTK in each): 5.20x median, 4.00x to 6.50x (CPU time "
      "6.93x median)");
  EXPECT_EQ(pairedSummary(r["goals"][1]), "");
}

TEST(PairedRounds, MedianBelowTheGoalIsNotMet) {
  nlohmann::json r = threeGoals();
  r["goals"][1]["speedup"] = 6.0;
  r["goals"][1]["met"] = true;
  Fake f{{300.0, 700.0}};
  runPairedRounds(r, 2, {"linear", "preintegration"}, f.hooks(), 5.0);
  // Two goals paired at once: both shellmarch frames, then one VTK process for both.
  EXPECT_EQ(f.calls, "S512 S512 V S512 S512 V ");
  EXPECT_DOUBLE_EQ(r["goals"][1]["paired"]["ratio_median"].get<double>(), 5.0);
  EXPECT_TRUE(r["goals"][1]["met"].get<bool>());  // 5.0 >= 5
  Fake g{{300.0, 600.0}};
  nlohmann::json r2 = threeGoals();
  r2["goals"][1]["met"] = true;
  runPairedRounds(r2, 2, {"linear"}, g.hooks(), 5.0);
  EXPECT_DOUBLE_EQ(r2["goals"][1]["paired"]["ratio_median"].get<double>(), 4.5);
  EXPECT_FALSE(r2["goals"][1]["met"].get<bool>());
}

TEST(PairedRounds, VtkFailureKeepsTheRoundsDone) {
  nlohmann::json r = threeGoals();
  Fake f{{600.0, 600.0, 600.0}};
  f.failAt = 1;
  runPairedRounds(r, 3, {"preintegration"}, f.hooks(), 5.0);
  EXPECT_EQ(f.calls, "S512 V S512 V ");  // no third round after the failure
  const auto& g = r["goals"][0];
  EXPECT_EQ(g["paired"]["rounds"].size(), 1u);
  EXPECT_EQ(g["paired_error"].get<std::string>(), "round 2: VTK crashed");
  EXPECT_DOUBLE_EQ(g["paired"]["ratio_median"].get<double>(), 6.0);
  EXPECT_NE(pairedSummary(g).find("paired rounds stopped: round 2: VTK crashed"),
            std::string::npos);
}

TEST(PairedRounds, AnyExceptionFromVtkKeepsTheRoundsDone) {
  nlohmann::json r = threeGoals();
  Fake f{{600.0, 600.0, 600.0}};
  f.failAt = 1;
  f.foreignError = true;
  runPairedRounds(r, 3, {"preintegration"}, f.hooks(), 5.0);
  EXPECT_EQ(r["goals"][0]["paired"]["rounds"].size(), 1u);
  EXPECT_EQ(r["goals"][0]["paired_error"].get<std::string>(), "round 2: VTK's JSON is truncated");
}

TEST(PairedRounds, NoRoundsNoChange) {
  nlohmann::json r = threeGoals();
  const nlohmann::json before = r;
  Fake f{{}};
  runPairedRounds(r, 0, {"preintegration"}, f.hooks(), 5.0);
  runPairedRounds(r, 3, {"homogeneous"}, f.hooks(), 5.0);  // no goal of that integrator
  EXPECT_EQ(f.calls, "");
  EXPECT_EQ(r, before);
}

}  // namespace
}  // namespace sm::app::bench
