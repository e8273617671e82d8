#include "bench/render_measure.h"

#include <sys/resource.h>

#include "bench/bench_common.h"
#include "common/timer.h"
#include "compositor/deep_compositor.h"
#include "render/renderer.h"

namespace sm::app::bench {
namespace {

double processCpuMs() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  auto ms = [](const timeval& t) { return double(t.tv_sec) * 1e3 + double(t.tv_usec) * 1e-3; };
  return ms(u.ru_utime) + ms(u.ru_stime);
}

}  // namespace

RenderMeasurement measureRender(session::RankSession& session, const render::RenderSettings& s,
                                int runs) {
  RenderMeasurement m;
  session.releaseRenderers();  // a cold start: nothing built, nothing compiled
  Timer setup;
  render::Renderer& renderer =
      session.renderer(s.width, s.height, comp::CompositorOptions{}, vk::Tracer::Auto);
  m.setupMs = setup.ms();
  render::FrameResult frame;
  for (int i = 0; i <= runs; ++i) {
    Timer wall;
    const double cpu0 = processCpuMs();
    frame = renderer.render(s, std::move(frame.pixels));
    const double cpu = processCpuMs() - cpu0;
    // Wall clock around render() (FrameTimings::totalMs is the same span measured inside).
    const double ms = wall.ms();
    if (i == 0) {
      m.coldMs = ms;
      continue;
    }
    m.totalMs.push_back(ms);
    m.cpuMs.push_back(cpu);
    m.traversalMs.push_back(frame.timings.traversalMs);
    m.scanMs.push_back(frame.timings.scanMs);
    m.marchMs.push_back(frame.timings.marchMs);
    m.compositeMs.push_back(frame.timings.compositeMs);
  }
  m.samples = gpu::sampleCount(frame.counters);
  m.elementSteps = gpu::elementStepCount(frame.counters);
  m.segments = frame.counters.segments;
  m.fragments = frame.counters.fragments;
  m.lostRays = frame.counters.lostRays;
  m.boxExits = frame.counters.boxExits;
  m.shellQueries = frame.counters.shellQueries;
  m.cacheRetraces = frame.counters.cacheRetraces;
  m.fused = frame.timings.fused;
  m.image = scene::Image(s.width, s.height);
  m.image.pixels = std::move(frame.pixels);
  session.releaseRenderers();  // the lists go with the measurement, as the next one starts cold
  return m;
}

nlohmann::json toJson(const RenderMeasurement& m) {
  const double total = median(m.totalMs);
  nlohmann::json j;
  j["setup_ms"] = m.setupMs;
  j["cold_first_frame_ms"] = m.coldMs;
  j["warm_runs"] = m.totalMs.size();
  j["warm_ms"] = total;
  j["warm_cpu_ms"] = median(m.cpuMs);
  j["frames_per_second"] = total > 0 ? 1e3 / total : 0.0;
  j["samples"] = m.samples;
  j["samples_per_second"] = total > 0 ? double(m.samples) / (total * 1e-3) : 0.0;
  // Elements the marcher walked through: its cost grows with these as much as with samples.
  j["element_steps"] = m.elementSteps;
  j["element_steps_per_second"] = total > 0 ? double(m.elementSteps) / (total * 1e-3) : 0.0;
  j["segments"] = m.segments;
  j["fragments"] = m.fragments;
  j["lost_rays"] = m.lostRays;
  j["box_exits"] = m.boxExits;
  j["shell_queries"] = m.shellQueries;
  j["cache_retraces"] = m.cacheRetraces;
  j["fused"] = m.fused;
  j["stages_ms"] = {{"traversal", median(m.traversalMs)},
                    {"scan", median(m.scanMs)},
                    {"march", median(m.marchMs)},
                    {"composite", median(m.compositeMs)}};
  j["warm_ms_all"] = m.totalMs;
  return j;
}

}  // namespace sm::app::bench
