// GPU frame timings of `shellmarch bench render`: one prepared scene at one image size.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "render/render_settings.h"
#include "scene/image.h"
#include "session/rank_session.h"

namespace sm::app::bench {

struct RenderMeasurement {
  double setupMs = 0;  // compositor and renderer construction (pipelines)
  double coldMs = 0;   // the first frame: Mesa compiles shaders on first dispatch
  std::vector<double> totalMs, traversalMs, scanMs, marchMs, compositeMs;  // warm frames
  // Processor time of this process per warm frame (lavapipe's threads included): unlike the wall
  // clock it does not grow when other processes share the cores.
  std::vector<double> cpuMs;
  uint64_t samples = 0, elementSteps = 0, segments = 0, fragments = 0, lostRays = 0;  // per frame
  uint64_t boxExits = 0, shellQueries = 0, cacheRetraces = 0;
  bool fused = false;  // one trace pass (traversal and marching together), FrameTimings::fused
  scene::Image image;  // the last frame
};

// A new compositor and renderer (setupMs), their first frame, which compiles the pipelines
// (coldMs), then `runs` warm frames of the same view, on `session`'s scene.
RenderMeasurement measureRender(session::RankSession& session,
                                const render::RenderSettings& settings, int runs);

// Medians, frames and samples per second; the per-frame lists too.
nlohmann::json toJson(const RenderMeasurement& m);

}  // namespace sm::app::bench
