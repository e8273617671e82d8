// `bench scale`'s Markdown: the table of measured rows and the analysis (scale_fit.h) as tables
// and lines. Internal to the benchmark.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace sm::app::bench {

// One row per element count and rank count, then a line per failed row with its error.
std::string scaleTable(const nlohmann::json& report);

// report["analysis"]: bytes per element by structure, growth exponents, strong and weak scaling,
// where the time to the first image goes at the largest size; then the memory check over frames
// (report["frames_check"]) and what render does not report.
std::string analysisText(const nlohmann::json& report);

}  // namespace sm::app::bench
