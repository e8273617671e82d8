// `shellmarch bench tracers`: the two tracers (ray queries from compute shaders, a ray tracing
// pipeline) on one scene and view, taking turns in rounds so that their ratio compares frames that
// saw the same machine (paired_rounds.h says why). Each tracer's frames, stages, throughput and
// first-frame cost, and whether their images agree bit for bit (they run the same arithmetic).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include "bench/bench_common.h"
#include "bench/bench_render_setup.h"
#include "bench/registry.h"
#include "cli/cli_checks.h"
#include "cli/cli_parsers.h"
#include "comm/reductions.h"
#include "comm/single_rank.h"
#include "common/error.h"
#include "common/timer.h"
#include "compositor/deep_compositor.h"
#include "gen/generate.h"
#include "pipeline/rank_pipeline.h"
#include "render/renderer.h"
#include "scene/camera.h"
#include "scene/transfer_function.h"
#include "scene/view_defaults.h"
#include "session/rank_session.h"

namespace sm::app::bench {
namespace {

struct TracerArgs {
  std::string mesh, field = "vortex", colormap = "cool-to-warm", view = "iso";
  std::string sizes = "512,1024", tracers, device, json, markdown, workDir = "out/bench";
  std::string analytic;  // a cube of gen::cube made in memory instead of --mesh (no file to write)
  int cubeN = 0;
  int rounds = 3, runs = 3;
};

// One tracer's renderer at one size, and its frames.
struct TracerRun {
  vk::Tracer tracer;
  render::Renderer* renderer = nullptr;  // the session's
  double setupMs = 0, coldMs = 0;
  std::vector<double> roundMs;  // per round: the median of its warm frames
  std::vector<double> totalMs, traceMs, marchMs, compositeMs;
  render::FrameResult last;
};

std::vector<vk::Tracer> tracersToRun(const TracerArgs& a, const vk::Context& ctx) {
  std::vector<vk::Tracer> out;
  if (a.tracers.empty()) {
    if (ctx.hasRayQuery()) out.push_back(vk::Tracer::Query);
    if (ctx.hasRayTracingPipeline()) out.push_back(vk::Tracer::Pipeline);
    return out;
  }
  for (const std::string& name : splitList(a.tracers)) {
    vk::Tracer t = parseTracer(name);
    if (t == vk::Tracer::Auto) t = ctx.tracer();
    const bool offered = t == vk::Tracer::Query ? ctx.hasRayQuery() : ctx.hasRayTracingPipeline();
    if (!offered)
      throw Error("--tracers: ", ctx.deviceName(), " offers no ", vk::tracerName(t), " tracer");
    if (std::find(out.begin(), out.end(), t) != out.end())
      throw Error("--tracers: '", name, "' is listed twice");
    out.push_back(t);
  }
  return out;
}

render::RenderSettings frameAt(const TracerArgs& a, const RankShare& share,
                               std::pair<double, double> range, int w, int h) {
  render::RenderSettings s;
  s.width = w;
  s.height = h;
  s.camera =
      scene::frameBounds(share.wholeBounds, scene::parseViewPreset(a.view), double(w) / h, 30);
  s.transferFunction = scene::makeTransferFunction(a.colormap);
  s.transferFunction.lo = range.first;
  s.transferFunction.hi = range.second;
  s.transferFunction.unitDistance = scene::defaultUnitDistance(share.wholeBounds);
  s.dt = scene::defaultStep(share.elementSize.mean(), share.wholeBounds);
  return s;
}

void warmFrames(TracerRun& r, const render::RenderSettings& s, int runs) {
  std::vector<double> round;
  for (int i = 0; i < runs; ++i) {
    Timer wall;
    r.last = r.renderer->render(s, std::move(r.last.pixels));
    const double ms = wall.ms();
    round.push_back(ms);
    r.totalMs.push_back(ms);
    r.traceMs.push_back(r.last.timings.traversalMs);
    r.marchMs.push_back(r.last.timings.marchMs);
    r.compositeMs.push_back(r.last.timings.compositeMs);
  }
  r.roundMs.push_back(median(round));
}

nlohmann::json runJson(const TracerRun& r, uint64_t elements, int w, int h) {
  const double ms = median(r.totalMs);
  const auto& c = r.last.counters;
  nlohmann::json j;
  j["tracer"] = vk::tracerName(r.tracer);
  j["setup_ms"] = r.setupMs;
  j["cold_first_frame_ms"] = r.coldMs;
  j["round_ms"] = r.roundMs;
  j["warm_ms"] = ms;
  j["trace_ms"] = median(r.traceMs);
  j["march_ms"] = median(r.marchMs);
  j["composite_ms"] = median(r.compositeMs);
  j["frames_per_second"] = 1e3 / ms;
  j["element_steps"] = gpu::elementStepCount(c);
  j["m_element_steps_per_second"] = double(gpu::elementStepCount(c)) / (ms * 1e3);
  j["m_pixels_per_second"] = double(w) * h / (ms * 1e3);
  j["m_samples_per_second"] = double(gpu::sampleCount(c)) / (ms * 1e3);
  // The paper's per-GPU figure: elements rendered times frames per second.
  j["elements_x_fps"] = double(elements) * 1e3 / ms;
  j["lost_rays"] = c.lostRays;
  return j;
}

// Pipeline over query per round, where both ran.
nlohmann::json pairedRatio(const TracerRun& query, const TracerRun& pipeline) {
  std::vector<double> ratios;
  for (size_t i = 0; i < query.roundMs.size(); ++i)
    ratios.push_back(pipeline.roundMs[i] / query.roundMs[i]);
  return {{"rounds", ratios},
          {"median", median(ratios)},
          {"min", *std::min_element(ratios.begin(), ratios.end())},
          {"max", *std::max_element(ratios.begin(), ratios.end())}};
}

bool sameImage(const render::FrameResult& a, const render::FrameResult& b) {
  return a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec4)) == 0;
}

nlohmann::json measureSize(const TracerArgs& a, session::RankSession& session,
                           const render::RenderSettings& s, const std::vector<vk::Tracer>& tracers,
                           uint64_t elements) {
  std::fprintf(stderr, "bench tracers: %dx%d, %d rounds of %d warm frames per tracer\n", s.width,
               s.height, a.rounds, a.runs);
  std::vector<TracerRun> runs(tracers.size());
  session.releaseRenderers();  // each size starts cold: its pipelines compile in its first frame
  for (size_t i = 0; i < tracers.size(); ++i) {
    TracerRun& r = runs[i];
    r.tracer = tracers[i];
    Timer setup;
    r.renderer = &session.renderer(s.width, s.height, comp::CompositorOptions{}, r.tracer);
    r.setupMs = setup.ms();
    Timer cold;
    r.last = r.renderer->render(s);
    r.coldMs = cold.ms();
  }
  for (int round = 0; round < a.rounds; ++round)
    for (TracerRun& r : runs) warmFrames(r, s, a.runs);
  nlohmann::json j;
  j["width"] = s.width;
  j["height"] = s.height;
  for (const TracerRun& r : runs) j["tracers"].push_back(runJson(r, elements, s.width, s.height));
  if (runs.size() == 2) {
    j["images_identical"] = sameImage(runs[0].last, runs[1].last);
    j["pipeline_over_query"] = pairedRatio(runs[0], runs[1]);
  }
  j["device_bytes_in_use"] = session.context().deviceMemoryInUse();
  return j;
}

std::string table(const nlohmann::json& report) {
  std::string t =
      "| size | tracer | warm frame ms | frames/s | trace ms | composite ms | "
      "M element steps/s | M pixels/s | elements x fps | first frame ms | "
      "pipeline / query (rounds) |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
  for (const auto& size : report["sizes"]) {
    const std::string name = sizeName(size["width"], size["height"]);
    for (const auto& r : size["tracers"]) {
      std::string ratio = "";
      if (r["tracer"] == "pipeline" && size.contains("pipeline_over_query")) {
        const auto& p = size["pipeline_over_query"];
        ratio = fixed(p["median"], 3) + " (" + fixed(p["min"], 3) + "-" + fixed(p["max"], 3) + ")" +
                (size["images_identical"].get<bool>() ? ", same image" : ", IMAGES DIFFER");
      }
      t += "| " + name + " | " + r["tracer"].get<std::string>() + " | " + fixed(r["warm_ms"], 2) +
           " | " + fixed(r["frames_per_second"], 1) + " | " + fixed(r["trace_ms"], 2) + " | " +
           fixed(r["composite_ms"], 2) + " | " + fixed(r["m_element_steps_per_second"], 1) + " | " +
           fixed(r["m_pixels_per_second"], 1) + " | " +
           fixed(r["elements_x_fps"].get<double>() / 1e6, 1) + " M | " +
           fixed(r["cold_first_frame_ms"], 0) + " | " + ratio + " |\n";
    }
  }
  return t;
}

// The mesh of --analytic (a cube made in memory: one cluster, the analytic fields), of --mesh, or
// the demo capsule; `path` names it in the report.
RankShare loadScene(const TracerArgs& a, std::string& path) {
  if (!a.analytic.empty()) {
    const auto split = gen::cubeSplitNamed(a.analytic);
    if (!split) throw Error("--analytic: '", a.analytic, "' is not a cube-* mesh of generate");
    if (a.cubeN < 1 || a.cubeN > 1000) throw Error("--cube-n: must be between 1 and 1000");
    if (!a.mesh.empty()) throw Error("--analytic: give it or --mesh, not both");
    path = concat(a.analytic, " ", a.cubeN, "^3 (in memory)");
    RankShare share;
    share.mesh = gen::cube(*split, a.cubeN);
    gen::addAnalyticFields(share.mesh, 1);
    share.wholeBounds = share.mesh.bounds();
    share.elementSize = scene::elementSizeSum(share.mesh);
    share.wholeElements = share.mesh.numCells();
    share.totalClusters = 1;
    share.clusters = {0};
    return share;
  }
  path = a.mesh;
  if (path.empty()) path = generatedMesh(a.workDir, demoMeshOptions());
  comm::SingleRank comm;
  ShareOptions so;
  so.read.fields = {a.field};
  return loadRankShare(path, so, comm);
}

void runTracerBench(const TracerArgs& a) {
  if (a.rounds < 1 || a.runs < 1) throw Error("--rounds and --runs: must be at least 1");
  const auto sizes = parseSizes("--sizes", a.sizes);
  vk::ContextOptions vo;
  vo.device = a.device;
  // Every tracer's renderer at a size is kept, so that their rounds interleave.
  session::RankSession session(vo, nullptr, session::SessionOptions{{}, vk::Tracer::Auto, 8});
  const vk::Context& ctx = session.context();
  const std::vector<vk::Tracer> tracers = tracersToRun(a, ctx);
  std::string path;
  RankShare share = loadScene(a, path);
  const mesh::Field* f = share.mesh.findField(a.field);
  if (!f) throw Error("--field: ", path, " has no point field '", a.field, "'");
  mesh::Range r = mesh::fieldRange(*f, 0);
  const std::pair<double, double> range =
      r.empty || !(r.lo < r.hi) ? std::pair{0.0, 1.0} : std::pair{r.lo, r.hi};
  PreparedShare prepared = prepareShare(share, prep::PrepOptions{true}, "", 0, 1);
  session.setScene(prepared.rank, std::move(prepared.rank.positions))
      .setScalars(fieldStep(share.mesh, prepared.rank, a.field, 0));
  const uint64_t elements = prepared.rank.numElements();
  nlohmann::json report;
  report["benchmark"] = "tracers";
  report["machine"] = machineJson();
  report["mesh"] = path;
  report["elements"] = elements;
  report["device"] = ctx.deviceName();
  report["options"] = {{"field", a.field}, {"rounds", a.rounds}, {"runs", a.runs}};
  for (auto [w, h] : sizes)
    report["sizes"].push_back(
        measureSize(a, session, frameAt(a, share, range, w, h), tracers, elements));
  const std::string md = table(report);
  std::printf("shellmarch bench tracers: %s (%llu elements) on %s\n%s\n%s", path.c_str(),
              (unsigned long long)elements, ctx.deviceName().c_str(),
              machineLine(report["machine"]).c_str(), md.c_str());
  if (!a.json.empty()) writeJsonFile(a.json, report);
  if (!a.markdown.empty()) writeTextFile(a.markdown, md);
  checkValidation(ctx);
}

}  // namespace

void configureTracerBench(CLI::App& cmd) {
  auto a = std::make_shared<TracerArgs>();
  cmd.add_option("--mesh", a->mesh, "Mesh to render (default: the demo capsule, generated once)");
  cmd.add_option("--field", a->field, "Point field (step 0)")->capture_default_str();
  cmd.add_option("--colormap", a->colormap, "Colour map")->capture_default_str();
  cmd.add_option("--view", a->view, "Framing view: iso, +x, -x, ...")->capture_default_str();
  cmd.add_option("--analytic", a->analytic,
                 "Instead of --mesh: a cube of generate --analytic (cube-tets6, cube-hexes, ...) "
                 "made in memory, one cluster, with the analytic fields (--field linear, ...)");
  cmd.add_option("--cube-n", a->cubeN, "Cells a side of the --analytic cube");
  cmd.add_option("--sizes", a->sizes, "Image sizes: N (square) or WxH, comma separated")
      ->capture_default_str();
  cmd.add_option("--tracers", a->tracers,
                 "Tracers to time: query and/or pipeline (default: every one the device offers)");
  cmd.add_option("--rounds", a->rounds, "Rounds, each tracer taking its turn in each")
      ->capture_default_str();
  cmd.add_option("--runs", a->runs, "Warm frames per tracer and round")->capture_default_str();
  cmd.add_option("--work-dir", a->workDir, "Where the generated demo mesh is kept")
      ->capture_default_str();
  cmd.add_option("--device", a->device, "Vulkan device index or name substring");
  cmd.add_option("--json", a->json, "Write the results as JSON to this file")
      ->check(writableFile());
  cmd.add_option("--markdown", a->markdown, "Write the table as Markdown to this file")
      ->check(writableFile());
  cmd.callback([a] { runTracerBench(*a); });
}

}  // namespace sm::app::bench
