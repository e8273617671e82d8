#include "pipeline/render_job.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>
#include <optional>

#include "common/error.h"
#include "common/fault_injection.h"
#include "common/file_util.h"
#include "common/memory.h"
#include "common/progress.h"
#include "common/timer.h"
#include "io/mesh_io.h"
#include "pipeline/frame_extras.h"
#include "pipeline/frame_writer.h"
#include "pipeline/memory_advice.h"
#include "pipeline/rank_pipeline.h"
#include "pipeline/render_setup.h"
#include "pipeline/render_stats.h"
#include "pipeline/sequence_stats.h"
#include "pipeline/step_loads.h"
#include "pipeline/step_source.h"
#include "pipeline/time_selection.h"
#include "render/preintegration.h"
#include "render/renderer.h"
#include "render/step_limits.h"
#include "scene/image.h"
#include "scene/legend.h"
#include "session/rank_session.h"
#include "vk/context.h"
#include "vk/vk_error.h"

namespace sm::app {
namespace {

// Range of `field` over the steps to render, over all ranks, reading one step at a time. No
// finite value anywhere is an error: every sample would be transparent, so the image would be
// empty, whatever the range.
std::pair<double, double> sequenceRange(const std::string& path, const StepSource& source,
                                        const std::string& field,
                                        const std::vector<uint64_t>& steps,
                                        comm::Communicator& comm) {
  std::vector<uint64_t> distinct = steps;
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  mesh::Range r;
  for (uint64_t s : distinct) r.extend(source.range(field, s));
  double lo = comm::minOf(comm, r.empty ? INFINITY : r.lo),
         hi = comm::maxOf(comm, r.empty ? -INFINITY : r.hi);
  if (!(lo <= hi))
    throw Error(path, ": field '", field, "' has no finite value in ",
                distinct.size() == 1 ? concat("step ", distinct[0])
                                     : concat("the ", distinct.size(), " steps rendered"),
                " (NaN and infinity render transparent: the image would be empty)");
  return {lo, hi};
}

// One frame of a run: the time step it shows, the camera it shows it from, and the number its
// image file takes in a sequence.
struct FramePlan {
  uint64_t step;
  scene::Camera camera;
  uint64_t number;
};

// The frames of one run. A time sequence is numbered by step. --orbit N turns the camera
// 360 / N degrees about its up axis each frame, starting from the camera given; with a single
// step that makes N frames, one full turn, numbered from 0; with several steps, one frame per step
// as without it, the camera turning as the steps go by.
std::vector<FramePlan> planFrames(const RenderJob& job, const std::vector<uint64_t>& steps,
                                  const render::RenderSettings& s, const mesh::Bounds& whole) {
  const bool turntable = job.orbit > 0 && steps.size() == 1;
  const size_t count = turntable ? size_t(job.orbit) : steps.size();
  std::vector<FramePlan> plan;
  plan.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    scene::Camera c = s.camera;
    if (job.orbit > 0) {
      // The angle from the frame index, not accumulated: the turn closes on the first frame.
      c = scene::turnAbout(s.camera,
                           2.0 * std::numbers::pi * double(i % size_t(job.orbit)) / job.orbit);
      // The step must hold from every eye, as makeSettings checked it from the first.
      render::checkStep(s.dt, c.eye, whole);
    }
    const uint64_t step = steps[turntable ? 0 : i];
    plan.push_back({step, c, turntable ? uint64_t(i) : step});
  }
  return plan;
}

// What the frames of one render touch.
struct Frames {
  const RenderJob& job;
  const std::vector<FramePlan>& plan;
  const StepSource& source;
  const std::string& field;
  const prep::PreparedRank& rank;
  render::GpuScene& gpu;
  render::Renderer& renderer;
  comp::DeepCompositor& compositor;
  const render::RenderSettings& settings;
  StatsReport& report;
  comm::Communicator& comm;
  FrameWriter& writer;  // rank 0's image files, encoded beside the frame loop
};

// A time sequence is numbered even when it turns out one frame long (--time all of a single
// step, --time 3:3): a script that globs name_NNNN.png must not find name.png instead. (--orbit 1,
// one frame from the camera given, is documented as the plain image.)
bool numbersFrames(const RenderJob& job, size_t frames) {
  return frames > 1 || selectsSequence(job.time);
}

// Statistics, extras and the image of a frame of the first run (collective).
void writeFrame(const Frames& f, const FramePlan& p, render::FrameResult& frame) {
  f.report.addFrame(p.step, p.camera, frame, f.renderer, f.compositor);
  const bool sequence = numbersFrames(f.job, f.plan.size());
  writeFrameExtras(f.job, f.compositor, frame.pixels, p.number, sequence, f.comm);
  if (f.comm.rank() == 0) {
    scene::Image img(f.job.width, f.job.height);
    img.pixels = std::move(frame.pixels);
    const scene::Background background = f.job.imageBackground();
    if (f.job.legend) scene::drawLegend(img, f.settings.transferFunction, f.field, background);
    if (f.job.frameSink)
      f.job.frameSink(img, p.number);
    else
      f.writer.write(framePath(f.job.out, p.number, sequence), img, background);  // a copy
    frame.pixels = std::move(img.pixels);  // back for the next frame (Renderer::render's reuse)
  }
}

// Renders the steps job.repeat times. Each frame's scalars were read and uploaded while the frame
// before rendered (prefetch), or are loaded at its start (--no-prefetch, and the first frame);
// a frame whose step is the one shown already (one step rendered repeatedly) loads nothing.
// Returns the first frame's timings (the startup statistics).
render::FrameTimings renderFrames(const Frames& f) {
  const size_t perRun = f.plan.size(), total = perRun * size_t(f.job.repeat);
  auto stepOf = [&](size_t i) { return f.plan[i % perRun].step; };
  render::RenderSettings settings = f.settings;
  SequenceStats stats(f.job.repeat, f.job.prefetch);
  StepLoads loads(f.source, f.rank, f.gpu);
  std::optional<uint64_t> shown;  // the step whose scalars frames read
  render::FrameResult frame;      // its pixels' storage is handed from frame to frame
  std::optional<render::FrameTimings> first;
  Progress progress("frame", total);
  if (total > 1 && (f.job.stats || !f.job.statsJson.empty())) {
    // The first frame compiles the pipelines; timed, it would dwarf the steady frames.
    loads.loadFor(f.field, stepOf(0));
    shown = stepOf(0);
    settings.camera = f.plan[0].camera;
    frame = f.renderer.render(settings);
    first = frame.timings;
  }
  for (size_t i = 0; i < total; ++i) {
    fault::atFrame(i);
    Timer frameTimer;
    render::ScalarSwitch scalars;
    if (shown != stepOf(i)) scalars = loads.loadFor(f.field, stepOf(i));
    shown = stepOf(i);
    if (f.job.prefetch && i + 1 < total && stepOf(i + 1) != stepOf(i))
      loads.prefetch(f.field, stepOf(i + 1));
    settings.camera = f.plan[i % perRun].camera;
    Timer renderTimer;
    frame = f.renderer.render(settings, std::move(frame.pixels));
    if (!first) first = frame.timings;
    const double renderMs = renderTimer.ms(), frameMs = frameTimer.ms();
    stats.addFrame(int(i / perRun), stepOf(i), frameMs, renderMs, scalars);
    if (i < perRun) writeFrame(f, f.plan[i], frame);
    // A rank's memory must not grow with the frames it renders: compared by bench scale.
    if (i == 0) f.report.setFrameMemory("host_bytes_after_first_frame_per_rank");
    progress.advance();
  }
  f.report.setFrameMemory("host_bytes_after_last_frame_per_rank");
  if (total > 1) f.report.setSequence(stats.summary(f.gpu, f.comm));
  return first.value_or(render::FrameTimings{});
}

// The files a job writes, by option (the heatmaps by their combined image; the per-rank ones sit
// beside it).
std::vector<std::pair<const char*, std::string>> outputFiles(const RenderJob& job) {
  std::vector<std::pair<const char*, std::string>> files;
  for (const auto& [option, path] : {std::pair<const char*, const std::string*>{"--out", &job.out},
                                     {"--stats-json", &job.statsJson},
                                     {"--l2-heatmap", &job.l2Heatmap},
                                     {"--dump-counts", &job.dumpCounts}})
    if (!path->empty()) files.emplace_back(option, *path);
  if (!job.heatmaps.empty()) files.emplace_back("--heatmaps", combinedHeatmapPath(job.heatmaps));
  return files;
}

bool sameFile(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (std::filesystem::equivalent(a, b, ec)) return true;
  // Files not yet written: by name, with "." and ".." and links in the existing part resolved.
  auto resolved = [&ec](const std::string& p) {
    return std::filesystem::weakly_canonical(std::filesystem::absolute(p, ec), ec);
  };
  const std::filesystem::path ra = resolved(a), rb = resolved(b);
  return !ec && ra == rb;
}

// The frame numbers `path` could hold: each run of four or more digits after a '_'.
std::vector<uint64_t> frameNumbersIn(const std::string& path) {
  std::vector<uint64_t> numbers;
  for (size_t i = path.find('_'); i != std::string::npos; i = path.find('_', i + 1)) {
    size_t e = i + 1;
    while (e < path.size() && path[e] >= '0' && path[e] <= '9') ++e;
    uint64_t n = 0;
    if (e - i - 1 >= 4 &&
        std::from_chars(path.data() + i + 1, path.data() + e, n).ec == std::errc())
      numbers.push_back(n);
  }
  return numbers;
}

// The option of the job whose numbered frame files `path` would overwrite (nullptr: none): an
// output's frame N is framePath(OUT, N) (the heatmaps' combined image framePath(PREFIX, N)_all).
const char* numberedOutputAt(const RenderJob& job, const std::string& path) {
  for (uint64_t n : frameNumbersIn(path)) {
    for (const auto& [option, base] : outputFiles(job)) {
      const bool heatmaps = option == std::string_view("--heatmaps");
      const std::string file = heatmaps ? combinedHeatmapPath(framePath(job.heatmaps, n, true))
                                        : framePath(base, n, true);
      if (option != std::string_view("--stats-json") && sameFile(path, file)) return option;
    }
  }
  return nullptr;
}

// Every file the job writes goes into a folder that exists, is not a folder itself, is not the
// mesh it reads, and is not another output: checked before any work, so that a mistyped
// --stats-json neither fails after the image was written (a half-done run) nor overwrites the
// input.
void checkOutputs(const RenderJob& job) {
  const auto outputs = outputFiles(job);
  for (size_t i = 0; i < outputs.size(); ++i) {
    const auto& [option, path] = outputs[i];
    const std::string dir = directoryOf(path);
    std::error_code ec;
    if (!dir.empty() && !std::filesystem::is_directory(dir, ec))
      throw Error(option, ": '", path, "' is in a folder that does not exist ('", dir, "')");
    if (std::filesystem::is_directory(path, ec)) throw Error(option, ": '", path, "' is a folder");
    for (size_t j = 0; j < i; ++j)
      if (sameFile(path, outputs[j].second))
        throw Error(option, ": '", path, "' is also the file of ", outputs[j].first);
  }
  // The statistics are one file; the others are numbered in a sequence, and may not be that file.
  if (!job.statsJson.empty() && (selectsSequence(job.time) || job.orbit > 1))
    if (const char* option = numberedOutputAt(job, job.statsJson))
      throw Error("--stats-json: '", job.statsJson, "' is also the name of a numbered frame of ",
                  option);
  if (!job.l2Heatmap.empty() && fileExtension(job.l2Heatmap) != ".png")
    throw Error("--l2-heatmap: '", job.l2Heatmap, "' must end in .png");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(job.mesh, ec)) return;  // the reader names the fault
  for (const std::string& input : io::meshFiles(job.mesh))
    for (const auto& [option, path] : outputs)
      if (sameFile(path, input))
        throw Error(option, ": '", path, "' is the mesh being read (", input, ")");
}

}  // namespace

void runRender(const RenderJob& job, comm::Communicator& comm) {
  session::checkRequest(frameRequest(job));
  checkOutputs(job);
  if (job.repeat < 1) throw Error("--repeat: must be at least 1, not ", job.repeat);
  if (job.orbit < 0) throw Error("--orbit: must be at least 1, not ", job.orbit);
  if (!job.frameSink && fileExtension(job.out) != ".png" && fileExtension(job.out) != ".pfm")
    throw Error("--out: '", job.out, "' must end in .png or .pfm");
  if (job.transparent && !job.frameSink && fileExtension(job.out) == ".pfm")
    throw Error("--background transparent: --out '", job.out,
                "' is a PFM, which has no alpha channel; write a .png");
  Timer total;
  // What the process holds before any mesh (code, libraries, MPI): the part of its memory that
  // does not grow with the mesh, which bench scale sets apart from what does.
  const uint64_t residentAtStart = currentResidentBytes();
  ShareOptions shareOptions = job.share;
  shareOptions.streamSteps = true;
  // Only the field rendered is read: a solver's file may hold dozens, and a component ("v[2]")
  // is a field only when asked for by name.
  const std::string cellDefault = defaultCellField(job, comm);
  if (!job.field.empty()) shareOptions.read.fields = {job.field};
  if (!cellDefault.empty()) shareOptions.read.fields = {cellDefault};
  RankShare share = loadRankShare(job.mesh, shareOptions, comm);
  const StepSource source(job.mesh, share, comm);
  const std::string field = cellDefault.empty() ? resolveField(job, share.mesh, comm) : cellDefault;
  const std::vector<uint64_t> steps = selectSteps(
      job.time,
      agreedStepCount(job.mesh, field, source.numSteps(field), share.mesh.numPoints() > 0, comm),
      share.mesh.timeValues, comm);
  const std::pair<double, double> range =
      job.range ? *job.range : sequenceRange(job.mesh, source, field, steps, comm);
  const double loadSeconds = total.seconds();  // with the range pass over the steps
  const uint64_t peakAfterLoad = peakResidentBytes();
  render::RenderSettings s = makeSettings(job, share, field, range);
  s.compositeMethod = job.composite;
  const std::vector<FramePlan> plan = planFrames(job, steps, s, share.wholeBounds);

  Timer prepTimer;
  PreparedShare prepared =
      prepareShare(share, prep::PrepOptions{job.compact}, job.cacheDir, comm.rank(), comm.size());
  const double prepSeconds = prepTimer.seconds();
  const uint64_t peakAfterPrepare = peakResidentBytes();  // before the device holds a copy
  session::RankSession session(contextOptions(job), comm::withPeers(comm),
                               session::SessionOptions{job.lists});
  const vk::Context& ctx = session.context();
  // Out of device memory becomes a message that says what would fit, not a Vulkan call's name.
  Timer uploadTimer;
  try {
    session.setScene(prepared.rank, std::move(prepared.rank.positions));
  } catch (const vk::BufferLimitError& e) {
    throw Error(e.what());  // names the buffer, the device's limit and how many more ranks
  } catch (const vk::DeviceMemoryError& e) {
    throw Error(sceneMemoryAdvice(e, ctx, prepared.rank, comm.size()));
  }
  render::GpuScene& gpu = session.scene();
  const double uploadSeconds = uploadTimer.seconds();  // buffers and acceleration structures
  try {
    render::Renderer& renderer = session.renderer(job.width, job.height);
    comp::DeepCompositor& compositor = session.compositor(job.width, job.height);

    StatsReport report(job, comm);
    report.setSetup(loadSeconds, prepSeconds, prepared.fromCache, prepared.rank, gpu,
                    ctx.deviceName(), vk::tracerName(renderer.tracer()), s);
    report.setHostMemory(residentAtStart, peakAfterLoad, peakAfterPrepare);
    report.setUpload(uploadSeconds);
    FrameWriter writer;
    const render::FrameTimings first =
        renderFrames({job, plan, source, field, prepared.rank, gpu, renderer, compositor, s, report,
                      comm, writer});
    writer.finish();  // every image written (or its error thrown) before the statistics
    report.setStartup(ctx, first.totalMs, first.traversalMs + first.marchMs);
    report.finish(ctx.validationErrors());
  } catch (const vk::DeviceMemoryError& e) {
    // Element-exact frames hold the pre-integrated transfer function beside the scene.
    const uint64_t table = s.integration == render::Integration::ElementExact
                               ? render::preintegrationDeviceBytes(s.transferFunction)
                               : 0;
    throw Error(listMemoryAdvice(e, ctx, gpu.deviceBytes() + table, job.width, job.height,
                                 job.lists, comm.size()));
  }
}

}  // namespace sm::app
