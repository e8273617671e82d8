// `shellmarch bench scale`: the cost curve (issue 41). For each element count a mesh is generated
// (`shellmarch generate`, a child process), then rendered by `mpirun -n R shellmarch render` at
// each rank count and image size, each a fresh process as a user runs it: what each stage costs,
// how it grows with N (the exponent of a log-log fit), how it scales over ranks, bytes per element
// by structure beside the paper's, and peak memory over the prepared size. Child processes, not
// threads: a 128 M-element row that runs out of memory is a failed row, not a failed benchmark.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "bench/bench_common.h"
#include "bench/registry.h"
#include "bench/scale_fit.h"
#include "bench/scale_report.h"
#include "bench/scale_run.h"
#include "cli/cli_checks.h"
#include "cli/commands.h"
#include "common/error.h"
#include "common/file_util.h"

namespace sm::app::bench {
namespace {

using Json = nlohmann::json;

// The grid to measure, parsed from the options.
struct ScalePlan {
  std::vector<uint64_t> elements;
  std::vector<int> ranks;
  std::vector<std::pair<int, int>> sizes;
  int repeat = 2;  // render --repeat: timed frames (render times frames only when over one)
};

std::vector<std::string> items(const std::string& option, const std::string& value) {
  std::vector<std::string> out;
  size_t b = 0;
  while (b <= value.size()) {
    size_t e = value.find(',', b);
    if (e == std::string::npos) e = value.size();
    out.push_back(value.substr(b, e - b));
    b = e + 1;
  }
  if (out.empty() || (out.size() == 1 && out[0].empty()))
    throw UsageError(option, ": needs at least one value");
  return out;
}

// "20000", "20K", "1.5M", "1G": at least 1, at most 10 G.
uint64_t parseElements(const std::string& item) {
  char* end = nullptr;
  double v = std::strtod(item.c_str(), &end);
  const std::string suffix = end ? end : "";
  if (suffix == "k" || suffix == "K") v *= 1e3;
  if (suffix == "m" || suffix == "M") v *= 1e6;
  if (suffix == "g" || suffix == "G") v *= 1e9;
  const bool known = suffix.empty() || (suffix.size() == 1 &&
                                        std::string("kKmMgG").find(suffix[0]) != std::string::npos);
  if (item.empty() || !known || !(v >= 1) || v > 1e10)
    throw UsageError("--elements: '", item, "' is not an element count (e.g. 20000, 20K, 4M, 1G)");
  return uint64_t(std::llround(v));
}

int parseRanks(const std::string& item) {
  char* end = nullptr;
  const long v = std::strtol(item.c_str(), &end, 10);
  if (item.empty() || *end || v < 1 || v > 4096)
    throw UsageError("--ranks: '", item, "' is not a rank count (1 .. 4096)");
  return int(v);
}

template <typename T>
std::vector<T> sortedUnique(std::vector<T> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

// Every option checked before anything runs: a typo must not surface after an hour of rows.
ScalePlan planOf(const ScaleArgs& a) {
  ScalePlan p;
  for (const std::string& s : items("--elements", a.elements))
    p.elements.push_back(parseElements(s));
  for (const std::string& s : items("--ranks", a.ranks)) p.ranks.push_back(parseRanks(s));
  p.elements = sortedUnique(p.elements);
  p.ranks = sortedUnique(p.ranks);
  try {
    p.sizes = parseSizes("--sizes", a.sizes);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  if (a.frames < 1) throw UsageError("--frames: must be at least 1, not ", a.frames);
  if (a.framesCheck != 0 && a.framesCheck < 3)
    throw UsageError("--frames-check: must be 0 (no check) or at least 3, not ", a.framesCheck);
  if (a.clusters < 0) throw UsageError("--clusters: must be at least 1, not ", a.clusters);
  if (a.method != "grid" && a.method != "gmsh")
    throw UsageError("--method: '", a.method, "' (use grid or gmsh)");
  if (a.dataDir.empty()) throw UsageError("--data-dir: must name a folder");
  p.repeat = std::max(2, a.frames);
  return p;
}

Json optionsJson(const ScaleArgs& a, const ScalePlan& p) {
  Json sizes = Json::array();
  for (auto [w, h] : p.sizes) sizes.push_back({{"width", w}, {"height", h}});
  const char* validation = std::getenv("SHELLMARCH_VALIDATION");
  return {{"elements", p.elements},
          {"ranks", p.ranks},
          {"sizes", sizes},
          {"frames", a.frames},
          {"frames_timed", p.repeat},
          {"method", a.method},
          {"clusters", a.clusters},
          {"data_dir", a.dataDir},
          {"keep", a.keep},
          {"frames_check", a.framesCheck},
          {"mpirun", a.mpirun},
          {"validation_layer", validation && std::string(validation) != "0"}};
}

// The row's stages as flat keys (scale_fit.h fits and compares them by key).
Json stagesOf(const Json& row) {
  Json st = Json::object();
  st["generate_s"] = jsonNumber(row["generate"], "seconds");
  if (row.contains("setup"))
    for (const char* k : kSetupStages) st[k] = row["setup"][k];
  for (const Json& s : row["sizes"])
    if (s["ok"].get<bool>())
      st[concat("warm_ms_", s["width"].get<int>(), "x", s["height"].get<int>())] =
          s["warm_frame_ms"];
  return st;
}

// One element count on one rank count: a render per image size; the first that succeeds gives
// the setup stages (each size's process loads and prepares the same mesh again).
Json measureRow(const ScaleArgs& a, const ScalePlan& p, const Json& gen, int ranks) {
  const uint64_t target = gen["elements_target"];
  Json row = {{"elements_target", target},
              {"ranks", ranks},
              {"generate", gen},
              {"elements", gen.value("elements", Json(target))},
              {"sizes", Json::array()}};
  if (gen.contains("error")) {
    row["error"] = "generate failed: " + gen["error"].get<std::string>();
  } else {
    for (auto [w, h] : p.sizes) {
      const std::string tag = concat("scale-", a.method, "-", target, "-r", ranks, "-", w, "x", h);
      Json rec = renderOnce(a, gen["mesh"].get<std::string>(), tag, ranks, w, h, p.repeat);
      if (rec["ok"].get<bool>() && !row.contains("setup")) row["setup"] = rec;
      if (!rec["ok"].get<bool>() && !row.contains("error"))
        row["error"] = concat(sizeName(w, h), ": ", rec["error"].get<std::string>());
      row["sizes"].push_back(std::move(rec));
    }
  }
  row["ok"] = row.contains("setup");
  if (row["ok"].get<bool>()) row["elements"] = row["setup"]["elements"];
  row["stages"] = stagesOf(row);
  return row;
}

// What the report estimates rather than measures, as it says it.
Json notReported() {
  return Json::array(
      {"wall time from process start to the first image: estimated as the "
       "process's wall time less its timed frames"});
}

void finishReport(const ScaleArgs& a, Json& report) {
  report["analysis"] = analyseScale(report);
  report["not_reported"] = notReported();
  const std::string md = scaleTable(report) + analysisText(report);
  const Json& o = report["options"];
  std::printf(
      "shellmarch bench scale: %s meshes, %zu element counts x %zu rank counts x %zu "
      "sizes, %d timed frames%s\n%s\n\n%s",
      o["method"].get<std::string>().c_str(), o["elements"].size(), o["ranks"].size(),
      o["sizes"].size(), o["frames_timed"].get<int>(),
      o["validation_layer"].get<bool>() ? " (validation layer on: timings include it)" : "",
      machineLine(report["machine"]).c_str(), md.c_str());
  if (!a.json.empty()) writeJsonFile(a.json, report);
  if (!a.markdown.empty()) writeTextFile(a.markdown, md);
}

void runScaleBench(const ScaleArgs& a) {
  if (!a.report.empty()) {  // the tables and fits again, from what a run measured
    Json report = Json::parse(readTextFile(a.report), nullptr, false);
    if (report.is_discarded() || report.value("benchmark", "") != "scale")
      throw Error(a.report, ": not the JSON of a bench scale run");
    for (Json& row : report["rows"]) row["stages"] = stagesOf(row);  // stages added since
    return finishReport(a, report);
  }
  const ScalePlan p = planOf(a);
  Json report;
  report["benchmark"] = "scale";
  report["machine"] = machineJson();
  report["options"] = optionsJson(a, p);
  report["meshes"] = Json::array();
  report["rows"] = Json::array();
  for (uint64_t target : p.elements) {
    const Json gen = generateMesh(a, target);
    report["meshes"].push_back(gen);
    for (int ranks : p.ranks) {
      report["rows"].push_back(measureRow(a, p, gen, ranks));
      // Written as rows finish: a run of hours killed at its largest mesh keeps the rest.
      if (!a.json.empty()) writeJsonFile(a.json, report);
    }
    if (a.framesCheck > 0 && target == p.elements.front() && !gen.contains("error"))
      report["frames_check"] = framesCheck(a, gen["mesh"].get<std::string>(), p.ranks.front(),
                                           p.sizes[0].first, p.sizes[0].second, a.framesCheck);
    if (!a.keep) removeMesh(gen["mesh"].get<std::string>());
  }
  finishReport(a, report);
  bool any = false;
  for (const Json& row : report["rows"]) any = any || row["ok"].get<bool>();
  if (!any) throw Error("bench scale: no row was measured (see the errors above)");
}

}  // namespace

void configureScaleBench(CLI::App& cmd) {
  auto a = std::make_shared<ScaleArgs>();
  cmd.add_option("--elements", a->elements,
                 "Element counts to generate, comma separated (20000, 20K, 4M, 1G)")
      ->capture_default_str();
  cmd.add_option("--ranks", a->ranks, "MPI rank counts to render each mesh on")
      ->capture_default_str();
  cmd.add_option("--sizes", a->sizes, "Image sizes: N (square) or WxH, comma separated")
      ->capture_default_str();
  cmd.add_option("--frames", a->frames,
                 "Warm frames timed per size (render --repeat; at least 2 are rendered)")
      ->capture_default_str();
  cmd.add_option("--method", a->method, "generate's method: grid (procedural) or gmsh")
      ->capture_default_str();
  cmd.add_option("--clusters", a->clusters, "generate --clusters (default: generate's choice)");
  cmd.add_option("--data-dir", a->dataDir,
                 "Folder for the generated meshes, render statistics and logs")
      ->capture_default_str();
  cmd.add_flag("--keep", a->keep,
               "Keep each generated mesh (reused by the next --keep run) instead of deleting it "
               "after its rows");
  cmd.add_option("--frames-check", a->framesCheck,
                 "Also render the smallest mesh N frames (e.g. 200): does a rank's memory after "
                 "the last frame exceed that after the first? (0: no check)")
      ->capture_default_str();
  cmd.add_option("--mpirun", a->mpirun, "MPI launcher (Open MPI's: --oversubscribe is passed)")
      ->capture_default_str();
  cmd.add_option("--report", a->report,
                 "Analyse an earlier run's --json again (tables, fits, scaling) instead of "
                 "measuring")
      ->check(CLI::ExistingFile);
  cmd.add_option("--json", a->json, "Write the results as JSON to this file")
      ->check(writableFile());
  cmd.add_option("--markdown", a->markdown, "Write the tables as Markdown to this file")
      ->check(writableFile());
  cmd.callback([a] { runScaleBench(*a); });
}

}  // namespace sm::app::bench
