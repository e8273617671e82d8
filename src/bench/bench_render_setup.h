// What `shellmarch bench render`'s parts share: its options, the scenes measured once per run, and
// the frame settings of a size. Internal to the benchmark (bench_render.cpp measures shellmarch,
// bench_render_vtk.cpp runs the VTK peer and the paired rounds).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/bench_common.h"
#include "pipeline/rank_pipeline.h"
#include "pipeline/rank_share.h"
#include "render/render_settings.h"
#include "session/rank_session.h"
#include "vk/context.h"

namespace sm::app::bench {

struct RenderArgs {
  std::string mesh;  // "" = the demo capsule (ci/demo.sh's options), generated under workDir
  std::string field = "vortex", colormap = "cool-to-warm", view = "iso";
  double fovy = 30, opacityScale = 1, earlyTermination = 0.99, step = 0;  // step 0: default
  std::string stepText;  // --step as given (parsed like render's)
  std::string sizes = "512,1024", references = "grid,converged",
              integrators = "preintegration,linear";
  std::string coarser = "2,4";  // extra compacted runs at dt times these
  std::string exact = "1,4";    // element-exact runs at dt times these (dt bounds non-tet pieces)
  int runs = 3, vtkRuns = 3;
  int pairRounds = 3;  // paired_rounds.h
  std::string pairIntegrators = "preintegration";
  double refTolerance = 1e-4;
  std::string workDir = "out/bench", json, device, python = defaultPython();
  std::string tracer = "auto";
  bool noVtk = false;
  // The first-image block (first_image.cpp): its size ("none": skipped), rounds, and whether it
  // is all that runs.
  std::string firstImage = "256x256";
  int firstImageRuns = 3;
  bool onlyFirstImage = false;
};

// Everything measured once per run: the mesh on the host (for the reference) and on the device,
// compacted and plain.
struct Scenes {
  RankShare share;  // whole mesh (fields kept; geometry moved into preparation)
  mesh::UnstructuredMesh refMesh;
  std::vector<float> values;  // field step 0 in mesh order
  std::pair<double, double> range;
  PreparedShare compact, plain;
  nlohmann::json setup;
};

// The frame settings of the benchmark's view at w x h: the field's range, the default step unless
// --step, the framing view.
render::RenderSettings settingsFor(const RenderArgs& a, const Scenes& sc, int w, int h);

// "a,b,c" -> {a, b, c}; empty items dropped.
std::vector<std::string> splitList(const std::string& s);

// VTK's ray cast mapper on the sizes measured (entries of report["sizes"]): its report, or
// {"available": false, "reason": ...} without VTK or with --no-vtk.
nlohmann::json runVtk(const RenderArgs& a, const Scenes& sc, const std::string& mesh,
                      const nlohmann::json& sizes);

// VTK's whole process (Python start, import, read, one frame, PNG; under xvfb-run where there is
// no display) for one image of `size` (camera included), `runs` times: the median seconds, or
// {"available": false, ...}.
nlohmann::json vtkFirstImage(const RenderArgs& a, const Scenes& sc, const std::string& mesh,
                             const nlohmann::json& size, int runs);

// The camera of `s` as VTK's job and the report take it.
nlohmann::json cameraJson(const scene::Camera& c);

// Paired rounds (paired_rounds.h) of the compacted scene's equal-error runs against VTK, into
// report.
void pairWithVtk(const RenderArgs& a, const Scenes& sc, const std::string& mesh,
                 session::RankSession& compact, nlohmann::json& report);

}  // namespace sm::app::bench
