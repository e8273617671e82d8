// The VTK peer of `shellmarch bench render`: its job file (the same mesh, view, size and transfer
// function), its runs, and the paired rounds that alternate shellmarch's equal-error frames with
// VTK's (paired_rounds.h).
#include <algorithm>
#include <filesystem>

#include "bench/bench_render_setup.h"
#include "bench/paired_rounds.h"
#include "bench/render_measure.h"
#include "bench/render_report.h"
#include "common/check.h"
#include "common/error.h"
#include "common/file_util.h"

namespace sm::app::bench {
namespace {

nlohmann::json vtkJob(const RenderArgs& a, const Scenes& sc, const std::string& mesh,
                      const nlohmann::json& sizes, const std::vector<std::string>& integrators,
                      const std::string& outDir) {
  render::RenderSettings s = settingsFor(a, sc, 1, 1);
  const auto& tf = s.transferFunction;
  nlohmann::json table = nlohmann::json::array();
  for (const glm::vec4& e : tf.table) table.push_back({e.r, e.g, e.b, e.a});
  nlohmann::json job;
  job["mesh"] = std::filesystem::absolute(mesh).string();
  job["array"] = sc.setup["array"];
  job["runs"] = a.vtkRuns;
  job["integrators"] = integrators;
  job["out_dir"] = std::filesystem::absolute(outDir).string();
  job["tf"] = {{"lo", tf.lo},
               {"hi", tf.hi},
               {"table", table},
               {"opacity_scale", tf.opacityScale},
               {"unit_distance", tf.unitDistance}};
  for (const auto& sz : sizes)
    job["sizes"].push_back(
        {{"width", sz["width"]}, {"height", sz["height"]}, {"view", sz["camera"]}});
  return job;
}

// VTK's script on `sizes` (entries of report["sizes"]) with `integrators`; `tag` names its job,
// result and log files in outDir.
PeerRun vtkRun(const RenderArgs& a, const Scenes& sc, const std::string& mesh,
               const nlohmann::json& sizes, const std::vector<std::string>& integrators,
               const std::string& outDir, const std::string& tag) {
  std::filesystem::create_directories(outDir);
  const std::string jobPath = joinPath(outDir, tag + "_job.json");
  writeJsonFile(jobPath, vtkJob(a, sc, mesh, sizes, integrators, outDir));
  return runPeer({a.python,
                  "vtk_render.py",
                  {"--job", jobPath},
                  joinPath(outDir, tag + ".json"),
                  joinPath(outDir, tag + ".log"),
                  true});
}

}  // namespace

nlohmann::json vtkFirstImage(const RenderArgs& a, const Scenes& sc, const std::string& mesh,
                             const nlohmann::json& size, int runs) {
  if (a.noVtk) return {{"available", false}, {"reason", "--no-vtk"}};
  RenderArgs once = a;
  once.vtkRuns = 0;
  const std::string integrator = splitList(a.pairIntegrators).front();
  std::vector<double> seconds;
  for (int i = 0; i < runs; ++i) {
    PeerRun run = vtkRun(once, sc, mesh, nlohmann::json::array({size}), {integrator},
                         joinPath(a.workDir, "first-image"), "vtk_first_image");
    if (!run.ok) return {{"available", false}, {"reason", run.error}};
    seconds.push_back(run.seconds);
  }
  return {{"available", true},
          {"integrator", integrator},
          {"seconds", median(seconds)},
          {"seconds_all", seconds}};
}

nlohmann::json runVtk(const RenderArgs& a, const Scenes& sc, const std::string& mesh,
                      const nlohmann::json& sizes) {
  if (a.noVtk) return {{"available", false}, {"reason", "--no-vtk"}};
  std::fprintf(stderr, "rendering with VTK (%d warm frames per size and integrator)\n", a.vtkRuns);
  PeerRun run = vtkRun(a, sc, mesh, sizes, splitList(a.integrators), a.workDir, "vtk_render");
  if (!run.ok) {
    std::fprintf(stderr, "VTK peer not measured: %s\n", run.error.c_str());
    return {{"available", false}, {"reason", run.error}};
  }
  run.result["available"] = true;
  return run.result;
}

namespace {

// The settings of shellmarch's run `label` at image size `size` (an entry of report["sizes"]).
render::RenderSettings settingsOfRun(const RenderArgs& a, const Scenes& sc,
                                     const nlohmann::json& size, const std::string& label) {
  render::RenderSettings s =
      settingsFor(a, sc, size["width"].get<int>(), size["height"].get<int>());
  if (label == "shellmarch compacted") return s;
  const nlohmann::json* run = nullptr;
  for (const auto& m : size["shellmarch"]["compacted_coarser"])
    if (m["label"].get<std::string>() == label) run = &m;
  SM_CHECK_MSG(run, concat("no run '", label, "' at this size"));  // goals name runs of their size
  s.dt = (*run)["dt"].get<double>();
  if (run->value("integration", "") == "element-exact")
    s.integration = render::Integration::ElementExact;
  if (run->value("stage_split", false)) s.segmentCacheBytes = 0;
  return s;
}

const nlohmann::json& sizeOfGoal(const nlohmann::json& report, const nlohmann::json& goal) {
  const nlohmann::json* size = nullptr;
  for (const auto& s : report["sizes"])
    if (s["width"] == goal["width"] && s["height"] == goal["height"]) size = &s;
  SM_CHECK(size);
  return *size;
}

}  // namespace

void pairWithVtk(const RenderArgs& a, const Scenes& sc, const std::string& mesh,
                 session::RankSession& compact, nlohmann::json& report) {
  if (a.pairRounds < 1 || !report["vtk"]["available"].get<bool>()) return;
  const std::vector<std::string> integrators = splitList(a.pairIntegrators);
  std::fprintf(stderr, "paired rounds: %d, shellmarch then VTK (%s) in each\n", a.pairRounds,
               a.pairIntegrators.c_str());
  int round = 0;
  PairedRoundHooks hooks;
  hooks.shellmarch = [&](const nlohmann::json& g) {
    const nlohmann::json& size = sizeOfGoal(report, g);
    RenderMeasurement m = measureRender(
        compact, settingsOfRun(a, sc, size, g["equal_error_run"].get<std::string>()), a.runs);
    return FrameTime{median(m.totalMs), median(m.cpuMs)};
  };
  hooks.vtk = [&](const std::vector<const nlohmann::json*>& goals) {
    nlohmann::json sizes = nlohmann::json::array();
    for (const nlohmann::json* g : goals) {
      const nlohmann::json& s = sizeOfGoal(report, *g);
      if (std::find(sizes.begin(), sizes.end(), s) == sizes.end()) sizes.push_back(s);
    }
    ++round;
    PeerRun run = vtkRun(a, sc, mesh, sizes, integrators, joinPath(a.workDir, "paired"),
                         concat("vtk_round", round));
    if (!run.ok) throw Error("VTK: ", run.error);
    std::vector<FrameTime> out;
    for (const nlohmann::json* g : goals)
      for (const auto& vs : run.result["sizes"])
        if (vs["width"] == (*g)["width"] && vs["height"] == (*g)["height"])
          for (const auto& v : vs["integrators"])
            if (v["integrator"] == (*g)["vtk_integrator"])
              out.push_back({v["warm_ms"].get<double>(), v["warm_cpu_ms"].get<double>()});
    return out;
  };
  runPairedRounds(report, a.pairRounds, integrators, hooks, kRenderSpeedGoal);
}

}  // namespace sm::app::bench
