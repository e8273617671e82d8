#include "bench/scale_fit.h"

#include <algorithm>
#include <cmath>

#include "bench/bench_common.h"
#include "common/error.h"

namespace sm::app::bench {
namespace {

// The paper's breakdown of prepared memory (connectivity, compacted elements, shell BVH).
constexpr double kPaperConnectivity = 0.6272, kPaperElements = 0.1711, kPaperShell = 0.1274;
constexpr double kTargetPeakOverPrepared = 2.5;

using Json = nlohmann::json;

std::vector<int> rankCounts(const Json& report) {
  return report["options"]["ranks"].get<std::vector<int>>();
}

const Json* findRow(const Json& report, uint64_t target, int ranks) {
  for (const Json& row : report["rows"])
    if (row["elements_target"] == target && row["ranks"] == ranks && row["ok"].get<bool>())
      return &row;
  return nullptr;
}

double stage(const Json& row, const std::string& key) {
  return jsonNumber(row["stages"], key);
}

// Stages that depend on the ranks (generation does not), for the scaling tables.
std::vector<StageName> rankStages(const Json& report) {
  std::vector<StageName> out;
  for (const StageName& s : scaleStages(report))
    if (s.key != "generate_s" && s.key != "context_s" && s.key != "upload_s" && s.key != "other_s")
      out.push_back(s);
  return out;
}

Json exponents(const Json& report) {
  Json out = Json::array();
  for (int r : rankCounts(report))
    for (const StageName& s : scaleStages(report)) {
      std::vector<double> n, t;
      for (const Json& row : report["rows"])
        if (row["ranks"] == r && row["ok"].get<bool>()) {
          n.push_back(jsonNumber(row, "elements"));
          t.push_back(stage(row, s.key));
        }
      const LogLogFit f = fitLogLog(n, t);
      if (f.points >= 2)
        out.push_back({{"ranks", r},
                       {"stage", s.key},
                       {"exponent", f.exponent},
                       {"prefactor", f.prefactor},
                       {"r2", f.r2},
                       {"points", f.points}});
    }
  return out;
}

// Speed-up of each stage at fixed N over the fewest ranks measured.
Json strong(const Json& report) {
  Json out = Json::array();
  const std::vector<int> ranks = rankCounts(report);
  for (uint64_t target : report["options"]["elements"].get<std::vector<uint64_t>>()) {
    const Json* base = findRow(report, target, ranks.front());
    for (size_t i = 1; base && i < ranks.size(); ++i) {
      const Json* row = findRow(report, target, ranks[i]);
      for (const StageName& s : rankStages(report)) {
        if (!row) continue;
        const double speedup = stage(*base, s.key) / stage(*row, s.key);
        out.push_back({{"elements_target", target},
                       {"base_ranks", ranks.front()},
                       {"ranks", ranks[i]},
                       {"stage", s.key},
                       {"speedup", speedup},
                       {"efficiency", speedup * ranks.front() / ranks[i]}});
      }
    }
  }
  return out;
}

// Time at N0 elements on R0 ranks over time at N0 * R / R0 on R ranks (the same elements per
// rank), where --elements has that count.
Json weak(const Json& report) {
  Json rows = Json::array();
  const std::vector<int> ranks = rankCounts(report);
  const auto targets = report["options"]["elements"].get<std::vector<uint64_t>>();
  for (uint64_t n0 : targets)
    for (size_t i = 1; i < ranks.size(); ++i) {
      const double want = double(n0) * ranks[i] / ranks.front();
      const Json* base = findRow(report, n0, ranks.front());
      for (uint64_t n : targets) {
        const Json* row = findRow(report, n, ranks[i]);
        if (!base || !row || std::abs(double(n) - want) > 0.01 * want) continue;
        Json j = {{"base_elements_target", n0},
                  {"base_ranks", ranks.front()},
                  {"elements_target", n},
                  {"ranks", ranks[i]}};
        for (const StageName& s : rankStages(report))
          j["efficiency"][s.key] = stage(*base, s.key) / stage(*row, s.key);
        rows.push_back(j);
      }
    }
  if (rows.empty())
    return {{"available", false},
            {"reason",
             "no element count in --elements is R / R0 times another on a rank count measured"}};
  return {{"available", true}, {"rows", rows}};
}

// Bytes per element by structure on rank 0, and the memory target (per rank: what reading and
// preparing held over the prepared size).
Json memoryRow(const Json& row) {
  const Json& m = row["setup"]["memory_rank0"];
  const double elements = jsonNumber(row["setup"], "elements_rank0");
  const double total = jsonNumber(m, "prepared_bytes");
  Json j = {{"elements_target", row["elements_target"]},
            {"ranks", row["ranks"]},
            {"elements_rank0", elements}};
  for (const char* k : {"vertices", "connectivity", "compacted_elements", "shell",
                        "acceleration_structures", "scalars_per_step", "prepared_bytes"})
    j["bytes_per_element"][k] = jsonNumber(m, k) / elements;
  j["shares"] = {{"connectivity", jsonNumber(m, "connectivity") / total},
                 {"compacted_elements", jsonNumber(m, "compacted_elements") / total},
                 {"shell", jsonNumber(m, "shell") / total},
                 {"acceleration_structures", jsonNumber(m, "acceleration_structures") / total},
                 {"shell_and_bvh",
                  (jsonNumber(m, "shell") + jsonNumber(m, "acceleration_structures")) / total}};
  j["paper_shares"] = {{"connectivity", kPaperConnectivity},
                       {"compacted_elements", kPaperElements},
                       {"shell_and_bvh", kPaperShell}};
  const double ratio = jsonNumber(row["setup"], "mesh_peak_over_prepared");
  j["mesh_peak_over_prepared"] = ratio;
  j["mesh_peak_over_prepared_target"] = kTargetPeakOverPrepared;
  j["mesh_peak_over_prepared_met"] = ratio <= kTargetPeakOverPrepared;
  return j;
}

// Shares of the time to the first image at the largest element count measured.
Json timeShares(const Json& report) {
  Json out = Json::array();
  uint64_t largest = 0;
  for (const Json& row : report["rows"])
    if (row["ok"].get<bool>()) largest = std::max(largest, row["elements_target"].get<uint64_t>());
  for (const Json& row : report["rows"]) {
    if (!row["ok"].get<bool>() || row["elements_target"] != largest) continue;
    const double total = stage(row, "first_image_s");
    Json j = {{"elements_target", largest}, {"ranks", row["ranks"]}, {"first_image_s", total}};
    for (const char* k : kSetupStages) j["shares"][k] = stage(row, k) / total;
    j["pipelines_share"] = jsonNumber(row["setup"], "pipelines_s") / total;
    out.push_back(j);
  }
  return out;
}

}  // namespace

double jsonNumber(const nlohmann::json& j, const std::string& dottedPath) {
  const Json* at = &j;
  size_t b = 0;
  while (b <= dottedPath.size()) {
    size_t e = dottedPath.find('.', b);
    if (e == std::string::npos) e = dottedPath.size();
    const std::string key = dottedPath.substr(b, e - b);
    if (!at->is_object() || !at->contains(key)) return NAN;
    at = &(*at)[key];
    b = e + 1;
  }
  return at->is_number() ? at->get<double>() : NAN;
}

LogLogFit fitLogLog(const std::vector<double>& n, const std::vector<double>& t) {
  std::vector<double> x, y;
  for (size_t i = 0; i < n.size() && i < t.size(); ++i)
    if (n[i] > 0 && t[i] > 0 && std::isfinite(n[i]) && std::isfinite(t[i])) {
      x.push_back(std::log(n[i]));
      y.push_back(std::log(t[i]));
    }
  LogLogFit f;
  f.points = int(x.size());
  double mx = 0, my = 0;
  for (size_t i = 0; i < x.size(); ++i) mx += x[i] / x.size(), my += y[i] / x.size();
  double sxx = 0, sxy = 0, syy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (f.points < 2 || sxx <= 0) {  // one size (or the same N twice): no slope to fit
    f.points = std::min(f.points, 1);
    return f;
  }
  f.exponent = sxy / sxx;
  f.prefactor = std::exp(my - f.exponent * mx);
  f.r2 = syy > 0 ? sxy * sxy / (sxx * syy) : 1.0;
  return f;
}

std::vector<StageName> scaleStages(const nlohmann::json& report) {
  std::vector<StageName> s = {{"generate_s", "generate s"},
                              {"load_s", "load s"},
                              {"prepare_s", "prepare s"},
                              {"context_s", "Vulkan context s"},
                              {"upload_s", "upload + AS build s"},
                              {"first_frame_s", "first frame s (with pipelines)"},
                              {"other_s", "other s (MPI start, exit)"},
                              {"first_image_s", "first image s (wall)"}};
  for (const Json& size : report["options"]["sizes"]) {
    const int w = size["width"], h = size["height"];
    s.push_back({concat("warm_ms_", w, "x", h), "warm frame ms " + sizeName(w, h)});
  }
  return s;
}

nlohmann::json analyseScale(const nlohmann::json& report) {
  Json a;
  a["exponents"] = exponents(report);
  a["strong"] = strong(report);
  a["weak"] = weak(report);
  a["memory"] = Json::array();
  for (const Json& row : report["rows"])
    if (row["ok"].get<bool>()) a["memory"].push_back(memoryRow(row));
  a["time_shares"] = timeShares(report);
  return a;
}

}  // namespace sm::app::bench
