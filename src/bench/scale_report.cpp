#include "bench/scale_report.h"

#include <cmath>

#include "bench/bench_common.h"
#include "bench/scale_fit.h"
#include "common/error.h"

namespace sm::app::bench {
namespace {

using Json = nlohmann::json;
constexpr double kMiB = 1024.0 * 1024.0;

std::string mib(double bytes) {
  return fixed(bytes / kMiB, 1);
}

std::string percent(double share) {
  return fixed(100.0 * share, 2);
}

// "1.00M" for a count, as the options spell them.
std::string count(double n) {
  if (!std::isfinite(n)) return "n/a";
  if (n >= 1e9) return fixed(n / 1e9, 2) + "G";
  if (n >= 1e6) return fixed(n / 1e6, 2) + "M";
  if (n >= 1e3) return fixed(n / 1e3, 1) + "K";
  return fixed(n, 0);
}

std::vector<std::string> generateCells(const Json& gen, bool first) {
  if (!first || gen.is_null()) return {"", "", ""};
  if (gen.contains("error")) return {"failed", "n/a", "n/a"};
  const std::string reused = gen.value("reused", false) ? " (kept)" : "";
  return {fixed(jsonNumber(gen, "seconds"), 2) + reused,
          fixed(jsonNumber(gen, "elements_per_second") / 1e6, 2),
          mib(jsonNumber(gen, "peak_rss_bytes"))};
}

std::string bytesTable(const Json& report) {
  Table t({"elements", "ranks", "vertices", "connectivity", "compacted el.", "shell", "BLAS + TLAS",
           "scalars", "total B/el", "conn. % (paper 62.72)", "elements % (paper 17.11)",
           "shell + BVH % (paper 12.74)"},
          2);
  int shown = 0;
  for (const Json& m : report["analysis"]["memory"]) {
    // One rank count per element count: the fewest, whose rank 0 holds the most of the mesh.
    if (m["ranks"] != report["options"]["ranks"][0]) continue;
    const Json& b = m["bytes_per_element"];
    const Json& s = m["shares"];
    t.add({count(jsonNumber(m, "elements_rank0")), std::to_string(m["ranks"].get<int>()),
           fixed(jsonNumber(b, "vertices"), 2), fixed(jsonNumber(b, "connectivity"), 2),
           fixed(jsonNumber(b, "compacted_elements"), 2), fixed(jsonNumber(b, "shell"), 2),
           fixed(jsonNumber(b, "acceleration_structures"), 2),
           fixed(jsonNumber(b, "scalars_per_step"), 2), fixed(jsonNumber(b, "prepared_bytes"), 2),
           percent(jsonNumber(s, "connectivity")), percent(jsonNumber(s, "compacted_elements")),
           percent(jsonNumber(s, "shell_and_bvh"))});
    ++shown;
  }
  if (!shown) return "";
  return "\nPrepared bytes per element by structure (rank 0, render's memory_rank0):\n\n" + t.str();
}

std::string exponentTable(const Json& report) {
  const Json& fits = report["analysis"]["exponents"];
  if (fits.empty()) return "\nGrowth exponents: fewer than two element counts measured.\n";
  std::vector<std::string> headers = {"stage"};
  for (int r : report["options"]["ranks"]) headers.push_back(concat("k at ", r, " rank(s) (r²)"));
  Table t(headers);
  for (const StageName& s : scaleStages(report)) {
    std::vector<std::string> row = {s.label};
    for (int r : report["options"]["ranks"]) {
      std::string cell = "n/a";
      for (const Json& f : fits)
        if (f["ranks"] == r && f["stage"] == s.key)
          cell =
              fixed(f["exponent"].get<double>(), 2) + " (" + fixed(f["r2"].get<double>(), 2) + ")";
      row.push_back(cell);
    }
    t.add(row);
  }
  return "\nGrowth exponents k of t ~ N^k (least squares on log t against log N):\n\n" + t.str();
}

std::string strongTable(const Json& report) {
  const Json& rows = report["analysis"]["strong"];
  if (rows.empty()) return "\nStrong scaling: one rank count measured (or no pair of rows).\n";
  const std::vector<int> ranks = report["options"]["ranks"].get<std::vector<int>>();
  std::vector<std::string> headers = {"--elements", "stage"};
  for (size_t i = 1; i < ranks.size(); ++i) headers.push_back(concat("speed-up at ", ranks[i]));
  Table t(headers, 2);
  for (uint64_t n : report["options"]["elements"].get<std::vector<uint64_t>>())
    for (const StageName& s : scaleStages(report)) {
      std::vector<std::string> row = {count(double(n)), s.label};
      bool any = false;
      for (size_t i = 1; i < ranks.size(); ++i) {
        std::string cell = "";
        for (const Json& r : rows)
          if (r["elements_target"] == n && r["ranks"] == ranks[i] && r["stage"] == s.key) {
            cell = fixed(jsonNumber(r, "speedup"), 2);
            any = true;
          }
        row.push_back(cell);
      }
      if (any) t.add(row);
    }
  return concat("\nStrong scaling: each stage's time on ", ranks.front(),
                " rank(s) over its time on R ranks, same mesh:\n\n") +
         t.str();
}

std::string weakTable(const Json& report) {
  const Json& weak = report["analysis"]["weak"];
  if (!weak["available"].get<bool>())
    return "\nWeak scaling: not measured (" + weak["reason"].get<std::string>() +
           "); strong scaling only.\n";
  std::vector<std::string> headers = {"--elements", "ranks"};
  std::vector<std::string> keys;  // in the stages' order (a JSON object's is alphabetical)
  for (const StageName& s : scaleStages(report))
    if (weak["rows"][0]["efficiency"].contains(s.key)) {
      keys.push_back(s.key);
      headers.push_back(s.label);
    }
  Table t(headers, 2);
  for (const Json& r : weak["rows"]) {
    std::vector<std::string> row = {
        count(r["base_elements_target"].get<double>()) + " -> " +
            count(r["elements_target"].get<double>()),
        concat(r["base_ranks"].get<int>(), " -> ", r["ranks"].get<int>())};
    for (const std::string& k : keys) row.push_back(fixed(jsonNumber(r["efficiency"], k), 2));
    t.add(row);
  }
  return "\nWeak scaling efficiency (the same elements per rank; 1 is perfect):\n\n" + t.str();
}

std::string shareLines(const Json& report) {
  std::string out;
  for (const Json& s : report["analysis"]["time_shares"]) {
    const Json& sh = s["shares"];
    out += concat("Where the time goes at ", count(s["elements_target"].get<double>()), " on ",
                  s["ranks"].get<int>(), " rank(s): first image in ",
                  fixed(jsonNumber(s, "first_image_s"), 2), " s = load ",
                  percent(jsonNumber(sh, "load_s")), "%, prepare ",
                  percent(jsonNumber(sh, "prepare_s")), "%, Vulkan context ",
                  percent(jsonNumber(sh, "context_s")), "%, ", percent(jsonNumber(sh, "upload_s")),
                  "% upload + AS build, first frame ", percent(jsonNumber(sh, "first_frame_s")),
                  "% (pipelines ", percent(jsonNumber(s, "pipelines_share")), "%), other ",
                  percent(jsonNumber(sh, "other_s")), "% (MPI start, exit)\n");
  }
  return out.empty() ? out : "\n" + out;
}

std::string framesCheckLine(const Json& report) {
  if (!report.contains("frames_check")) return "";
  const Json& c = report["frames_check"];
  if (c.contains("error"))
    return concat("\nMemory over ", c["frames"].get<int>(),
                  " frames: not measured: ", c["error"].get<std::string>(), "\n");
  return concat("\nMemory over ", c["frames"].get<int>(), " frames (", c["ranks"].get<int>(),
                " rank(s), ", sizeName(c["width"], c["height"]),
                "): ", mib(jsonNumber(c, "before_bytes")), " MiB -> ",
                mib(jsonNumber(c, "after_bytes")), " MiB, ",
                c["grows"].get<bool>() ? "GROWS" : "does not grow", " (",
                c["measure"].get<std::string>(), ")\n");
}

}  // namespace

std::string scaleTable(const nlohmann::json& report) {
  std::vector<std::string> headers = {
      "elements",      "ranks",   "status",       "generate s", "gen M el/s",
      "gen peak MiB",  "load s",  "prepare s",    "context s",  "upload + AS s",
      "first frame s", "other s", "first image s"};
  for (const Json& size : report["options"]["sizes"])
    headers.push_back("warm ms " + sizeName(size["width"], size["height"]));
  for (const char* h :
       {"peak MiB/rank", "run peak MiB", "prepared MiB r0", "peak/prepared", "mesh peak/prepared"})
    headers.push_back(h);
  Table t(headers, 3);
  std::string failures;
  Json previous;
  for (const Json& row : report["rows"]) {
    const bool firstOfMesh = row["elements_target"] != previous;
    previous = row["elements_target"];
    const bool ok = row["ok"].get<bool>();
    std::vector<std::string> cells = {count(jsonNumber(row, "elements")),
                                      std::to_string(row["ranks"].get<int>()),
                                      ok ? "ok" : "failed"};
    for (std::string& c : generateCells(row["generate"], firstOfMesh)) cells.push_back(c);
    const Json& st = row["stages"];
    for (const char* k : kSetupStages) cells.push_back(fixed(jsonNumber(st, k), 2));
    for (const Json& size : report["options"]["sizes"])
      cells.push_back(fixed(jsonNumber(st, concat("warm_ms_", size["width"].get<int>(), "x",
                                                  size["height"].get<int>())),
                            1));
    const Json& setup = row.value("setup", Json());
    cells.push_back(mib(jsonNumber(setup, "host_peak_after_setup_bytes")));
    cells.push_back(mib(jsonNumber(setup, "process_peak_rss_bytes")));
    cells.push_back(mib(jsonNumber(setup, "prepared_bytes_rank0")));
    cells.push_back(fixed(jsonNumber(setup, "peak_over_prepared"), 2));
    cells.push_back(fixed(jsonNumber(setup, "mesh_peak_over_prepared"), 2));
    t.add(cells);
    if (row.contains("error"))
      failures +=
          concat("- ", count(row["elements_target"].get<double>()), " on ", row["ranks"].get<int>(),
                 " rank(s): ", row["error"].get<std::string>(), "\n");
  }
  // The driver's own memory (lavapipe: ~150 MiB a rank) is in the peak: small meshes read high.
  const std::string note =
      "\npeak MiB/rank: the largest rank's host peak after setup (driver included); run peak: "
      "the largest process's over the whole run, frames included (wait4); peak/prepared: "
      "over rank 0's prepared bytes (fixed driver memory dominates small meshes, and lavapipe's "
      "device copy of the scene is host memory); mesh peak/prepared: the peak through reading "
      "and preparing, less what the process held before reading, over the prepared bytes "
      "(target <= 2.5), the largest over the ranks of each rank's own ratio. other: first image "
      "less load, prepare, context, upload and first frame (MPI start, exit).\n";
  return t.str() + note + (failures.empty() ? "" : "\nFailed or partial rows:\n" + failures);
}

std::string analysisText(const nlohmann::json& report) {
  std::string out = bytesTable(report) + exponentTable(report) + strongTable(report) +
                    weakTable(report) + shareLines(report) + framesCheckLine(report);
  if (report.contains("not_reported")) {
    out += "\nNot reported by render (estimated or left out here):\n";
    for (const Json& line : report["not_reported"]) out += "- " + line.get<std::string>() + "\n";
  }
  return out;
}

}  // namespace sm::app::bench
