// Image errors, goals and the printed tables of `shellmarch bench render`.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/image.h"

namespace sm::app::bench {

// The render benchmark's goal: shellmarch at least this many times VTK's speed at equal or lower
// error (issue 3).
inline constexpr double kRenderSpeedGoal = 5.0;

// One image size's images: shellmarch's (by label) and the CPU references ("grid", "converged").
struct RenderImages {
  std::vector<std::pair<std::string, scene::Image>> renderers;
  std::map<std::string, scene::Image> references;
};

// Adds report["sizes"][i]["errors"] (every image, VTK's read from its PNGs, against every
// reference, with the 8-bit rounding floor) and report["goals"] (speed-up over each VTK
// integrator and whether shellmarch's error is equal or lower).
void addErrorsAndGoals(nlohmann::json& report, const std::vector<RenderImages>& images);

void printRenderTables(const nlohmann::json& report);

}  // namespace sm::app::bench
