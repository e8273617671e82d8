// What the benchmarks share: the machine they ran on, option lists, medians, Markdown tables,
// JSON output, measurements in a child process, cached generated meshes and the Python peers.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "gen/generate.h"
#include "mesh/unstructured_mesh.h"
#include "render/render_settings.h"
#include "vk/context.h"

namespace sm::app::bench {

// CPU model, logical cores, memory, load averages, kernel: timings on a shared machine mean
// little without the load they were taken under.
nlohmann::json machineJson();
std::string machineLine(const nlohmann::json& machine);  // one line for the table header

double median(std::vector<double> values);

// "1000000,5000000" or "1M,5M" (k and M suffixes); each at least 1.
std::vector<uint64_t> parseCounts(const std::string& option, const std::string& value);
// "512,1024" (square) or "640x480,..."
std::vector<std::pair<int, int>> parseSizes(const std::string& option, const std::string& value);

std::string fixed(double value, int digits);
std::string sizeName(int width, int height);  // "512²" or "640x480"

// A Markdown table whose columns are padded to line up in a terminal; the first `textColumns`
// columns are left-aligned, the rest (numbers) right-aligned.
class Table {
 public:
  explicit Table(std::vector<std::string> headers, size_t textColumns = 1)
      : headers_(std::move(headers)), textColumns_(textColumns) {}
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  std::string str() const;

 private:
  std::vector<std::string> headers_;
  size_t textColumns_;
  std::vector<std::vector<std::string>> rows_;
};

void writeJsonFile(const std::string& path, const nlohmann::json& json);
// Text (a Markdown table) to `path`, written to a temporary name and renamed.
void writeTextFile(const std::string& path, const std::string& text);

// The frame the features and counts benchmarks render: `m` framed from the iso view, field `f`'s
// step-0 range mapped through `colormap`, the default unit distance of `m`, and half its mean
// element size as the step (scene::elementStep: these cubes are coarse enough for the default
// step's cap, which came after their recorded figures).
render::RenderSettings isoFrame(const mesh::UnstructuredMesh& m, const mesh::Field& f,
                                const std::string& colormap, int width, int height);

// A benchmark that ran under the validation layer and saw errors must not report numbers.
void checkValidation(const vk::Context& ctx);

// Runs fn in a forked child and returns what it returned. The child starts from this process's
// small footprint, so its peak resident size (after resetPeakResident) is the measured work's
// own. An exception in the child is rethrown here as sm::Error with its message.
nlohmann::json runInChild(const std::function<nlohmann::json()>& fn);

// The demo capsule's options, as ci/demo.sh generates it (300 k elements, 8 clusters, 4 steps).
gen::CfdMeshOptions demoMeshOptions();
// The cached gmsh mesh for these options under workDir, generated (in a child process, which
// takes minutes for millions of elements) when it is not there yet.
std::string generatedMesh(const std::string& workDir, const gen::CfdMeshOptions& options);

// argv with stdout and stderr sent to logPath and `env` ("NAME=value") added to the environment:
// its exit status (-1: could not start; 128 + signal when killed) and the peak resident size of
// it and of every descendant it reaped (for mpirun: its largest rank).
struct SpawnResult {
  int status = -1;
  uint64_t peakRssBytes = 0;
};
SpawnResult spawnLogged(const std::vector<std::string>& argv, const std::string& logPath,
                        const std::vector<std::string>& env = {});

// A Python peer (a VTK script shipped beside the tool). The script writes its result as JSON to
// the file given after --json; stdout and stderr go to logPath.
struct PeerRun {
  bool ok = false;
  std::string error;  // why not, for the report (missing Python or VTK, a crash, ...)
  nlohmann::json result;
  double seconds = 0;  // the whole process, start to exit
};
struct PeerOptions {
  std::string python;  // interpreter with VTK
  std::string script;  // file name beside the tool, e.g. "vtk_prep.py"
  std::vector<std::string> args;
  std::string jsonOut, logPath;
  bool needsDisplay = false;  // OpenGL: run under xvfb-run when there is no $DISPLAY
};
PeerRun runPeer(const PeerOptions& options);

// /usr/bin/python3 when it exists (Debian's python3-vtk9 lives there, not in a pyenv), else
// python3.
std::string defaultPython();

// argv run with `env` ("NAME=value") added to this process's environment, stdout and stderr to
// logPath: its exit status (-1: it could not start), wall-clock seconds and, on failure, the
// log's tail.
struct ProcessResult {
  int status = -1;
  double seconds = 0;
  std::string error;
};
ProcessResult runProcess(const std::vector<std::string>& argv, const std::vector<std::string>& env,
                         const std::string& logPath);

}  // namespace sm::app::bench
