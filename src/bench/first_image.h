// `bench render`'s first-image block (docs/BENCHMARKS.md, "The first image"): what a user waits
// for one image, start to PNG, in a fresh process of `shellmarch render`, with cold caches
// (Mesa's and shellmarch's shader caches emptied) and warm ones (kept from the run before), beside
// VTK's whole process for the same image.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "bench/bench_render_setup.h"

namespace sm::app::bench {

nlohmann::json measureFirstImage(const RenderArgs& a, const Scenes& sc, const std::string& mesh);
void printFirstImage(const nlohmann::json& block);

}  // namespace sm::app::bench
