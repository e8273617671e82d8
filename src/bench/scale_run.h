// `bench scale`'s measurements: `shellmarch generate` and `mpirun shellmarch render` run as child
// processes, timed from outside (the wall clock a user waits) and with their peak resident size
// from wait4, and what each render's --stats-json says, reduced to one record per run. Internal to
// the benchmark (bench_scale.cpp runs the grid of sizes, scale_fit.cpp derives the curves).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sm::app::bench {

struct ScaleArgs {
  std::string elements = "1M,4M,16M,64M,128M", ranks = "1,2,4,8", sizes = "512,1024";
  std::string method = "grid";  // generate --method; gmsh: generate's default (no --method)
  std::string dataDir = "out/bench/scale-data", json, markdown, mpirun = "mpirun";
  std::string report;   // an earlier run's JSON to analyse again instead of measuring
  int frames = 3;       // warm frames per size (render --repeat; at least 2 are rendered)
  int clusters = 0;     // generate --clusters; 0: generate's default
  int framesCheck = 0;  // frames of the memory check; 0: no check
  bool keep = false;    // keep each generated mesh (default: deleted after its rows)
};

// A child process: exit status (-1: could not start; 128 + signal when killed), wall seconds,
// the peak resident size of it and its reaped descendants (for mpirun: the largest rank), and on
// failure the line that says why.
struct ChildRun {
  int status = -1;
  double seconds = 0;
  uint64_t peakRssBytes = 0;
  std::string error;
};
// argv with stdout and stderr to logPath.
ChildRun runChild(const std::vector<std::string>& argv, const std::string& logPath);

// The mesh of `target` elements under --data-dir (a name per method and target).
std::string scaleMeshPath(const ScaleArgs& a, uint64_t target);

// Generates the mesh of `target` elements (or reuses a --keep'd one and its record): elements
// written, seconds, elements per second, peak resident bytes, or "error".
nlohmann::json generateMesh(const ScaleArgs& a, uint64_t target);

// Removes a generated mesh: the .pvtu, its pieces and their folder when left empty.
void removeMesh(const std::string& path);

// One `mpirun -n ranks shellmarch render` of `mesh` at w x h with `repeat` timed frames: the
// record of the run (stages, memory, wall time), or {"ok": false, "error": ...}.
nlohmann::json renderOnce(const ScaleArgs& a, const std::string& mesh, const std::string& tag,
                          int ranks, int w, int h, int repeat);

// Whether a rank's memory grows with frames: `frames` frames against 2 of the same view.
nlohmann::json framesCheck(const ScaleArgs& a, const std::string& mesh, int ranks, int w, int h,
                           int frames);

}  // namespace sm::app::bench
