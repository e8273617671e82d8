#include "bench/paired_rounds.h"

#include <exception>

#include <algorithm>

#include "bench/bench_common.h"
#include "common/error.h"

namespace sm::app::bench {
namespace {

std::vector<nlohmann::json*> pairedGoals(nlohmann::json& report,
                                         const std::vector<std::string>& integrators) {
  std::vector<nlohmann::json*> out;
  if (!report.contains("goals")) return out;
  for (nlohmann::json& g : report["goals"]) {
    const std::string name = g["vtk_integrator"].get<std::string>();
    if (std::find(integrators.begin(), integrators.end(), name) == integrators.end()) continue;
    if (g["equal_error_run"].is_null()) continue;  // nothing of shellmarch's to pair
    out.push_back(&g);
  }
  return out;
}

void summarise(nlohmann::json& goal, double speedGoal) {
  nlohmann::json& p = goal["paired"];
  std::vector<double> ratios, cpuRatios;
  for (const auto& r : p["rounds"]) {
    ratios.push_back(r["ratio"].get<double>());
    cpuRatios.push_back(r["ratio_cpu"].get<double>());
  }
  if (ratios.empty()) return;
  p["ratio_median"] = median(ratios);
  p["ratio_min"] = *std::min_element(ratios.begin(), ratios.end());
  p["ratio_max"] = *std::max_element(ratios.begin(), ratios.end());
  p["ratio_cpu_median"] = median(cpuRatios);
  // The paired median is the steadier estimate of the two; the single-run ratio stays in
  // "speedup".
  goal["met"] = median(ratios) >= speedGoal;
}

}  // namespace

void runPairedRounds(nlohmann::json& report, int rounds,
                     const std::vector<std::string>& integrators, const PairedRoundHooks& hooks,
                     double speedGoal) {
  std::vector<nlohmann::json*> goals = pairedGoals(report, integrators);
  if (goals.empty() || rounds < 1) return;
  std::vector<const nlohmann::json*> view(goals.begin(), goals.end());
  for (nlohmann::json* g : goals) (*g)["paired"] = {{"rounds", nlohmann::json::array()}};
  for (int round = 0; round < rounds; ++round) {
    std::vector<FrameTime> ours;
    for (const nlohmann::json* g : view) ours.push_back(hooks.shellmarch(*g));
    std::vector<FrameTime> theirs;
    try {
      theirs = hooks.vtk(view);
      if (theirs.size() != goals.size())
        throw Error("VTK gave ", theirs.size(), " frame times for ", goals.size(), " cases");
    } catch (const std::exception& e) {
      // Not only Error: the VTK hook also creates folders and reads JSON, and the rounds already
      // done, and the report, must survive any of it.
      for (nlohmann::json* g : goals)
        (*g)["paired_error"] = concat("round ", round + 1, ": ", e.what());
      break;
    }
    for (size_t i = 0; i < goals.size(); ++i) {
      const FrameTime& a = ours[i];
      const FrameTime& b = theirs[i];
      (*goals[i])["paired"]["rounds"].push_back({{"shellmarch_ms", a.ms},
                                                 {"shellmarch_cpu_ms", a.cpuMs},
                                                 {"vtk_ms", b.ms},
                                                 {"vtk_cpu_ms", b.cpuMs},
                                                 {"ratio", b.ms / a.ms},
                                                 {"ratio_cpu", b.cpuMs / a.cpuMs}});
    }
  }
  for (nlohmann::json* g : goals) summarise(*g, speedGoal);
}

std::string pairedSummary(const nlohmann::json& goal) {
  if (!goal.contains("paired")) return "";
  const nlohmann::json& p = goal["paired"];
  std::string s;
  if (p.contains("ratio_median"))
    s = concat("paired rounds (", p["rounds"].size(),
               ", shellmarch then VTK in each): ", fixed(p["ratio_median"].get<double>(), 2),
               "x median, ", fixed(p["ratio_min"].get<double>(), 2), "x to ",
               fixed(p["ratio_max"].get<double>(), 2), "x (CPU time ",
               fixed(p["ratio_cpu_median"].get<double>(), 2), "x median)");
  if (goal.contains("paired_error"))
    s += concat(s.empty() ? "" : "; ",
                "paired rounds stopped: ", goal["paired_error"].get<std::string>());
  return s;
}

}  // namespace sm::app::bench
