// Paired rounds of `shellmarch bench render`: the speed-up over VTK measured with shellmarch and
// VTK taking turns, so that the ratio compares frames that saw the same machine.
//
// Why: the main tables time every shellmarch run first and VTK minutes later. On a shared machine
// the load changes in between, and VTK's caster moves more than shellmarch does (its 512² frame
// read 539 to 871 ms over runs a few hours apart), so one ratio per run says as much about the
// neighbours as about the renderers. Alternating rounds give one ratio per round; their median
// and spread are the speed-up and how far to trust it.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sm::app::bench {

// A median warm frame: wall clock and processor time, milliseconds.
struct FrameTime {
  double ms = 0, cpuMs = 0;
};

struct PairedRoundHooks {
  // shellmarch's frame for goal g (report["goals"][i]): its equal-error run at its size.
  std::function<FrameTime(const nlohmann::json& goal)> shellmarch;
  // VTK's frame for each of the goals, in their order (one VTK process per round); throws
  // sm::Error when VTK fails.
  std::function<std::vector<FrameTime>(const std::vector<const nlohmann::json*>& goals)> vtk;
};

// Runs `rounds` rounds over report["goals"] whose VTK integrator is listed in `integrators` and
// which have an equal-error run; a round times shellmarch for each such goal, then VTK for all of
// them. Each goal gets "paired": {"rounds": [{shellmarch_ms, vtk_ms, ratio, ...}], "ratio_median",
// "ratio_min", "ratio_max", "ratio_cpu_median"}, and "met" is then decided on the median ratio.
// A VTK failure ends the rounds: the goals keep the rounds done and get "paired_error".
void runPairedRounds(nlohmann::json& report, int rounds,
                     const std::vector<std::string>& integrators, const PairedRoundHooks& hooks,
                     double speedGoal);

// "paired rounds (3, shellmarch then VTK in each): 3.62x median, 3.21x to 4.08x (...)", or ""
// for a goal without them.
std::string pairedSummary(const nlohmann::json& goal);

}  // namespace sm::app::bench
