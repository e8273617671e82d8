// shellmarch bench prep [--elements 1000000,5000000 | --mesh FILE ...] [--threads 1] [--runs 3]
//                       [--formats cgns,exodus] [--work-dir out/bench] [--json FILE]
//                       [--python PY] [--no-vtk]
// Load and preparation throughput per stage and peak memory, with VTK's read and surface
// extraction of the same files in the same run (docs/BENCHMARKS.md). --formats also reads each
// mesh as CGNS and Exodus II copies written by those formats' libraries, against its .pvtu.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "bench/bench_common.h"
#include "bench/prep_measure.h"
#include "bench/registry.h"
#include "bench/solver_files.h"
#include "cli/cli_checks.h"
#include "common/error.h"
#include "common/file_util.h"
#include "io/mesh_io.h"
#include "prep/memory_report.h"

namespace sm::app::bench {
namespace {

constexpr double kTargetRate = 2e6;    // connectivity + shell + compaction, elements/s, one core
constexpr double kTargetMemory = 2.5;  // peak above the process's start / prepared size
constexpr double kPaperSavings = 0.7249;
constexpr double kTargetFormatRatio = 1.5;  // a solver format's load against the .pvtu's

struct PrepArgs {
  std::string elements = "1000000,5000000";
  std::vector<std::string> meshes;  // instead of generated ones
  std::vector<std::string> fields;
  std::vector<std::string> formats;  // cgns, exodus: copies measured beside each mesh
  unsigned threads = 1;
  int runs = 3;
  std::string workDir = "out/bench";
  std::string json;
  std::string python = defaultPython();
  bool noVtk = false;
};

std::vector<std::string> meshesToMeasure(const PrepArgs& a) {
  if (!a.meshes.empty()) return a.meshes;
  std::vector<std::string> paths;
  for (uint64_t n : parseCounts("--elements", a.elements)) {
    gen::CfdMeshOptions o;
    o.targetElements = n;
    o.hexBlock = true;  // all four element types
    paths.push_back(generatedMesh(a.workDir, o));
  }
  return paths;
}

// The copies of `mesh` in the formats asked for (written once, then reused as generated meshes
// are): format name and path.
std::vector<std::pair<std::string, std::string>> formatCopies(const PrepArgs& a,
                                                              const std::string& mesh) {
  std::vector<std::pair<std::string, std::string>> copies;
  std::optional<mesh::UnstructuredMesh> m;
  for (const std::string& f : a.formats) {
    const std::string path = joinPath(a.workDir, concat(std::filesystem::path(mesh).stem().string(),
                                                        f == "cgns" ? ".cgns" : ".exo"));
    if (!std::filesystem::exists(path)) {
      if (!m) m = io::readMesh(mesh);
      std::fprintf(stderr, "writing %s\n", path.c_str());
      if (f == "cgns")
        writeCgnsCopy(path, *m);
      else
        writeExodusCopy(path, *m);
    }
    copies.emplace_back(f, path);
  }
  return copies;
}

nlohmann::json vtkPeer(const PrepArgs& a, const std::string& mesh, int index) {
  if (a.noVtk) return {{"available", false}, {"reason", "--no-vtk"}};
  PeerOptions p;
  p.python = a.python;
  p.script = "vtk_prep.py";
  p.args = {mesh, "--runs", std::to_string(a.runs), "--threads", std::to_string(a.threads)};
  p.jsonOut = joinPath(a.workDir, concat("vtk_prep_", index, ".json"));
  p.logPath = joinPath(a.workDir, concat("vtk_prep_", index, ".log"));
  PeerRun run = runPeer(p);
  if (!run.ok) {
    std::fprintf(stderr, "VTK peer not measured: %s\n", run.error.c_str());
    return {{"available", false}, {"reason", run.error}};
  }
  run.result["available"] = true;
  return run.result;
}

std::string cell(const nlohmann::json& stage, double elements) {
  double s = stage["seconds"].get<double>();
  return concat(fixed(s, 3), " s (", fixed(elements / s / 1e6, 2), ")");
}

std::string met(bool ok) {
  return ok ? "met" : "NOT met";
}

void printTables(const nlohmann::json& report) {
  const unsigned threads = report["options"]["threads"].get<unsigned>();
  std::printf("shellmarch bench prep: %s\n", machineLine(report["machine"]).c_str());
  std::printf(
      "\nPreparation, %u reader thread(s), preparation on one core; median of %d runs: "
      "seconds (M elements/s)\n\n",
      threads, report["options"]["runs"].get<int>());
  std::vector<std::string> head = {"elements"};
  for (const PrepStage& st : prepStages()) head.push_back(st.title);
  head.insert(head.end(), {"conn + shell + compaction", "target ≥ 2 M/s"});
  Table speed(head);
  Table memory({"elements", "prepared", "peak RSS", "peak above start", "ratio", "target ≤ 2.5×",
                "compaction saves (paper 72.49%)"});
  Table vtk({"elements", "VTK read", "VTK weld", "vtkDataSetSurfaceFilter", "vtkGeometryFilter",
             "VTK read + weld + surface", "shellmarch load + conn + shell", "VTK peak RSS"});
  for (const auto& m : report["meshes"]) {
    const double n = m["elements"].get<double>();
    std::vector<std::string> row = {concat(m["elements"].get<uint64_t>())};
    for (const PrepStage& st : prepStages()) row.push_back(cell(m["stages"][st.key], n));
    row.push_back(cell(m["conn_shell_compaction"], n));
    row.push_back(met(m["targets"]["rate_met"].get<bool>()));
    speed.add(row);
    const auto& mp = m["memory_peak"];
    memory.add({concat(m["elements"].get<uint64_t>()), prep::formatBytes(mp["prepared_bytes"]),
                prep::formatBytes(mp["peak_bytes"]),
                prep::formatBytes(mp["peak_above_start_bytes"]),
                fixed(mp["ratio_peak_above_start"].get<double>(), 2) + "×",
                met(m["targets"]["memory_met"].get<bool>()),
                fixed(100 * m["compaction_savings"].get<double>(), 2) + "%"});
    const auto& v = m["vtk"];
    if (!v["available"].get<bool>()) {
      vtk.add({concat(m["elements"].get<uint64_t>()), "n/a: " + v["reason"].get<std::string>()});
      continue;
    }
    auto vs = [&](const char* k) {
      return concat(fixed(v[k].get<double>(), 3), " s (", fixed(n / v[k].get<double>() / 1e6, 2),
                    ")");
    };
    const double ours = m["stages"]["load"]["seconds"].get<double>() +
                        m["stages"]["connectivity"]["seconds"].get<double>() +
                        m["stages"]["shell"]["seconds"].get<double>();
    vtk.add({concat(m["elements"].get<uint64_t>()), vs("read_seconds"), vs("weld_seconds"),
             vs("surface_seconds"), vs("geometry_seconds"), vs("total_seconds"),
             concat(fixed(ours, 3), " s (", fixed(n / ours / 1e6, 2), ")"),
             prep::formatBytes(v["peak_rss_bytes"].get<uint64_t>())});
  }
  std::printf(
      "%s\nMemory: peak resident set of the measuring process (read + prepare) against the "
      "prepared size (memory report; no acceleration structures)\n\n%s\n",
      speed.str().c_str(), memory.str().c_str());
  std::printf("VTK %s (Python), same files, same run: seconds (M elements/s)\n\n%s",
              report["vtk_version"].get<std::string>().c_str(), vtk.str().c_str());
  Table formats({"elements", "format", "load", ".pvtu load", "ratio", "target ≤ 1.5×"}, 2);
  bool any = false;
  for (const auto& m : report["meshes"])
    for (const auto& f : m.value("formats", nlohmann::json::array())) {
      any = true;
      formats.add({concat(m["elements"].get<uint64_t>()), f["format"].get<std::string>(),
                   fixed(f["load_seconds"].get<double>(), 3) + " s",
                   fixed(m["stages"]["load"]["seconds"].get<double>(), 3) + " s",
                   fixed(f["ratio"].get<double>(), 2) + "×", met(f["met"].get<bool>())});
    }
  if (any)
    std::printf("\nThe same mesh read from the solvers' formats (median load, read + weld)\n\n%s",
                formats.str().c_str());
}

// Load of each copy in another format, against the mesh's own load.
nlohmann::json measureFormats(const PrepArgs& a, const std::string& path, const nlohmann::json& m) {
  nlohmann::json out = nlohmann::json::array();
  const double base = m["stages"]["load"]["seconds"].get<double>();
  for (const auto& [format, copy] : formatCopies(a, path)) {
    std::fprintf(stderr, "measuring %s (%d runs)\n", copy.c_str(), a.runs);
    std::vector<nlohmann::json> runs;
    for (int r = 0; r < a.runs; ++r) runs.push_back(measurePrepOnce({copy, a.fields, a.threads}));
    const nlohmann::json s = summarisePrepRuns(runs);
    const double load = s["stages"]["load"]["seconds"].get<double>();
    out.push_back({{"format", format},
                   {"file", copy},
                   {"elements", s["elements"]},
                   {"load_seconds", load},
                   {"ratio", load / base},
                   {"met", load / base <= kTargetFormatRatio}});
  }
  return out;
}

void runPrepBench(const PrepArgs& a) {
  if (a.runs < 1) throw Error("--runs: must be at least 1, got ", a.runs);
  if (a.threads < 1) throw Error("--threads: must be at least 1, got ", a.threads);
  std::filesystem::create_directories(a.workDir);
  nlohmann::json report;
  report["benchmark"] = "prep";
  report["machine"] = machineJson();
  report["options"] = {{"threads", a.threads}, {"runs", a.runs}, {"fields", a.fields}};
  report["targets"] = {{"conn_shell_compaction_elements_per_second", kTargetRate},
                       {"peak_over_prepared", kTargetMemory},
                       {"paper_compaction_savings", kPaperSavings}};
  report["vtk_version"] = "n/a";
  report["meshes"] = nlohmann::json::array();
  int index = 0;
  for (const std::string& path : meshesToMeasure(a)) {
    std::fprintf(stderr, "measuring %s (%d runs)\n", path.c_str(), a.runs);
    std::vector<nlohmann::json> runs;
    for (int r = 0; r < a.runs; ++r) runs.push_back(measurePrepOnce({path, a.fields, a.threads}));
    nlohmann::json m = summarisePrepRuns(runs);
    m["mesh"] = path;
    m["targets"] = {
        {"rate_met",
         m["conn_shell_compaction"]["elements_per_second"].get<double>() >= kTargetRate},
        {"memory_met", m["memory_peak"]["ratio_peak_above_start"].get<double>() <= kTargetMemory}};
    m["vtk"] = vtkPeer(a, path, index++);
    if (!a.formats.empty()) m["formats"] = measureFormats(a, path, m);
    if (m["vtk"].contains("vtk_version")) report["vtk_version"] = m["vtk"]["vtk_version"];
    report["meshes"].push_back(m);
  }
  report["load_average_after"] = machineJson()["load_average"];
  printTables(report);
  if (!a.json.empty()) writeJsonFile(a.json, report);
}

}  // namespace

void configurePrepBench(CLI::App& cmd) {
  auto a = std::make_shared<PrepArgs>();
  cmd.add_option("--elements", a->elements, "Generated capsule meshes to measure (e.g. 1M,5M)")
      ->capture_default_str();
  cmd.add_option("--mesh", a->meshes, "Measure these files instead of generated meshes");
  cmd.add_option("--field", a->fields, "Point fields to load (default: all, as render does)")
      ->check(nonEmptyName());
  cmd.add_option("--formats", a->formats,
                 "Also read each mesh from copies in these formats, against its .pvtu")
      ->delimiter(',')
      ->check(CLI::IsMember({"cgns", "exodus"}));
  cmd.add_option("--threads", a->threads, "Reader threads (preparation runs on one core)")
      ->capture_default_str();
  cmd.add_option("--runs", a->runs, "Runs per mesh (medians are reported)")->capture_default_str();
  cmd.add_option("--work-dir", a->workDir, "Generated meshes (reused) and peer outputs")
      ->capture_default_str();
  cmd.add_option("--json", a->json, "Write the results as JSON to this file")
      ->check(writableFile());
  cmd.add_option("--python", a->python, "Python with VTK (python3-vtk9)")->capture_default_str();
  cmd.add_flag("--no-vtk", a->noVtk, "Skip the VTK peer");
  cmd.callback([a] { runPrepBench(*a); });
}

}  // namespace sm::app::bench
