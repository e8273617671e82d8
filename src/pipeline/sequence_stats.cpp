#include "pipeline/sequence_stats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sm::app {
namespace {

// Waits this small are thread hand-over, not reading: the prefetch counts as hidden below it.
constexpr double kHiddenWaitMs = 0.5;

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / double(v.size());
}

// Sample standard deviation (0 for fewer than two values).
double stddev(const std::vector<double>& v) {
  if (v.size() < 2) return 0.0;
  const double m = mean(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / double(v.size() - 1));
}

nlohmann::json spread(double v, comm::Communicator& comm) {
  return {{"min", comm::minOf(comm, v)}, {"max", comm::maxOf(comm, v)}};
}

}  // namespace

void SequenceStats::addFrame(int run, uint64_t step, double frameMs, double renderMs,
                             const render::ScalarSwitch& scalars) {
  frames_.push_back({run, step, frameMs, renderMs, scalars});
}

nlohmann::json SequenceStats::summary(const render::GpuScene& gpu, comm::Communicator& comm) const {
  nlohmann::json perRun = nlohmann::json::array();
  std::vector<double> fps, frameMs, renderMs, waitMs, loadMs, uploadMs;
  for (size_t i = 0; i < frames_.size(); ++i) {
    const Frame& f = frames_[i];
    if (perRun.empty() || perRun.back()["run"] != f.run)
      perRun.push_back({{"run", f.run}, {"frames", nlohmann::json::array()}});
    nlohmann::json fr = {{"step", f.step},
                         {"frame_ms", comm::maxOf(comm, f.frameMs)},
                         {"render_ms", comm::maxOf(comm, f.renderMs)},
                         {"scalar_wait_ms", comm::maxOf(comm, f.scalars.waitMs)},
                         {"step_load_ms", comm::maxOf(comm, f.scalars.loadMs)},
                         {"upload_ms", comm::maxOf(comm, f.scalars.uploadMs)}};
    frameMs.push_back(fr["frame_ms"]);
    renderMs.push_back(fr["render_ms"]);
    if (i > 0) {  // the first frame's scalars are loaded before any prefetch can start
      waitMs.push_back(fr["scalar_wait_ms"]);
      loadMs.push_back(fr["step_load_ms"]);
      uploadMs.push_back(fr["upload_ms"]);
    }
    perRun.back()["frames"].push_back(fr);
  }
  for (auto& run : perRun) {
    double ms = 0;
    for (const auto& fr : run["frames"]) ms += fr["frame_ms"].get<double>();
    run["seconds"] = ms / 1e3;
    run["fps"] = ms > 0 ? double(run["frames"].size()) * 1e3 / ms : 0.0;
    fps.push_back(run["fps"]);
  }
  const double wait = mean(waitMs), work = mean(loadMs) + mean(uploadMs);
  nlohmann::json j;
  j["runs"] = runs_;
  j["steps_per_run"] = runs_ > 0 ? frames_.size() / size_t(runs_) : 0;
  j["frames"] = frames_.size();
  j["prefetch"] = prefetch_;
  j["fps_mean"] = mean(fps);
  j["fps_stddev"] = stddev(fps);
  j["fps_min"] = fps.empty() ? 0.0 : *std::min_element(fps.begin(), fps.end());
  j["fps_max"] = fps.empty() ? 0.0 : *std::max_element(fps.begin(), fps.end());
  j["frame_ms_mean"] = mean(frameMs);
  j["render_ms_mean"] = mean(renderMs);
  j["scalar_wait_ms_mean"] = wait;
  j["scalar_wait_ms_max"] = waitMs.empty() ? 0.0 : *std::max_element(waitMs.begin(), waitMs.end());
  j["step_load_ms_mean"] = mean(loadMs);
  j["upload_ms_mean"] = mean(uploadMs);
  j["prefetch_hidden_fraction"] = work > 0 ? std::clamp(1.0 - wait / work, 0.0, 1.0) : 1.0;
  j["prefetch_hidden"] = prefetch_ && (wait < kHiddenWaitMs || wait < 0.05 * work);
  j["geometry_builds"] = spread(double(gpu.geometryBuilds()), comm);
  j["scalar_uploads"] = spread(double(gpu.scalarUploads()), comm);
  j["per_run"] = perRun;
  return j;
}

void printSequenceSummary(const nlohmann::json& j) {
  std::printf(
      "  sequence: %llu frames x %d run(s), prefetch %s: %.2f fps mean over runs (stddev %.2f, "
      "min %.2f, max %.2f); frame %.1f ms mean (render %.1f ms)\n",
      (unsigned long long)j["steps_per_run"].get<uint64_t>(), j["runs"].get<int>(),
      j["prefetch"].get<bool>() ? "on" : "off", j["fps_mean"].get<double>(),
      j["fps_stddev"].get<double>(), j["fps_min"].get<double>(), j["fps_max"].get<double>(),
      j["frame_ms_mean"].get<double>(), j["render_ms_mean"].get<double>());
  std::printf(
      "    scalars: frames waited %.2f ms on average (max %.2f ms) for reading %.1f ms + "
      "upload %.1f ms per step: %s (%.0f%% hidden); geometry built %.0f time(s) per rank\n",
      j["scalar_wait_ms_mean"].get<double>(), j["scalar_wait_ms_max"].get<double>(),
      j["step_load_ms_mean"].get<double>(), j["upload_ms_mean"].get<double>(),
      j["prefetch_hidden"].get<bool>() ? "hidden" : "not hidden",
      100.0 * j["prefetch_hidden_fraction"].get<double>(),
      j["geometry_builds"]["max"].get<double>());
}

}  // namespace sm::app
