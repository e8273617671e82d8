// `bench scale`'s derived figures, from the rows it measured: how each stage's time grows with
// the element count (the exponent k of t ~ N^k, least squares on logarithms), strong and weak
// scaling over ranks, bytes per element by structure beside the paper's shares, peak memory over
// the prepared size, and where the time to the first image goes at the largest size.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sm::app::bench {

// The number at a dotted path ("startup.first_frame_ms"); NaN when missing, null or not a number
// (a field render does not report, a failed run).
double jsonNumber(const nlohmann::json& j, const std::string& dottedPath);

struct LogLogFit {
  double exponent = 0, prefactor = 0, r2 = 0;  // t = prefactor * N^exponent
  int points = 0;                              // fewer than 2: no fit
};
// Least squares of log(t) on log(n) over the pairs where both are positive and finite.
LogLogFit fitLogLog(const std::vector<double>& n, const std::vector<double>& t);

// The stages fitted and compared, as keys of a row's "stages" object ("warm_ms_512x512" ...)
// with their names in the tables.
struct StageName {
  std::string key, label;
};
std::vector<StageName> scaleStages(const nlohmann::json& report);
// A render's stages up to its first image, in the tables' order; first_image_s is their whole.
inline constexpr const char* kSetupStages[] = {
    "load_s", "prepare_s", "context_s", "upload_s", "first_frame_s", "other_s", "first_image_s"};

// The "analysis" block of the report, from report["rows"] (each with "elements_target",
// "elements", "ranks", "ok", "stages", "setup").
nlohmann::json analyseScale(const nlohmann::json& report);

}  // namespace sm::app::bench
