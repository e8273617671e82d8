#include "viewer/viewer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <thread>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/file_util.h"
#include "common/log.h"
#include "common/timer.h"
#include "pipeline/render_setup.h"
#include "scene/camera_file.h"
#include "scene/image.h"
#include "scene/legend.h"
#include "viewer/early_input.h"
#include "viewer/input.h"
#include "viewer/presenter.h"
#include "viewer/render_args.h"
#include "viewer/screen_image.h"
#include "viewer/script.h"
#include "viewer/view_scene.h"
#include "viewer/window.h"

namespace sm::view {
namespace {

class Viewer {
 public:
  Viewer(const app::RenderJob& job, const ViewOptions& options, comm::Communicator& comm);
  void run();

 private:
  bool root() const { return comm_.rank() == 0; }
  void gatherInput();
  void chooseRenderScale(const scene::Camera& before);
  bool paceStep(int32_t step);
  void applyEvents(std::vector<InputEvent>& events);
  void show(render::FrameResult& frame, uint64_t fragments);
  std::vector<std::string> overlayLines() const;
  void writeScreenshots();
  void finish();
  // --print-camera: the final camera and settings, and the render arguments that reproduce them.
  // Waits of the ranks other than 0 for the frame's state, over the session: the longest one's
  // wall time and the CPU time its main thread spent in them (collective: every rank calls it).
  struct StateWaits {
    double ms = 0, cpuMs = 0;
  };
  StateWaits otherRanksStateWaits();
  nlohmann::json report(uint64_t errors, const StateWaits& waits) const;

  const app::RenderJob& job_;
  const ViewOptions& options_;
  comm::Communicator& comm_;
  Script script_;
  std::unique_ptr<Window> window_;  // rank 0 only, as are presenter_, input_ and early_
  std::unique_ptr<ViewScene> scene_;
  std::unique_ptr<Presenter> presenter_;
  std::unique_ptr<InputHandler> input_;
  std::unique_ptr<EarlyInput> early_;
  ViewState state_;
  LocalRequests local_;
  std::vector<glm::vec4> lastPixels_;
  std::vector<glm::vec4> sparePixels_;  // the frame before's, handed to the next render
  int lastWidth_ = 0, lastHeight_ = 0;
  uint32_t framesShown_ = 0;
  uint32_t reducedFrames_ = 0;       // frames rendered at a reduced size while the camera moved
  ViewState shownState_;             // the state of the frame shown last
  uint64_t stoppedReads_ = 0;        // reads ahead stopped unfinished (finish(): summed over ranks)
  bool rangePassStopped_ = false;    // a close or quit came during a new field's range pass
  uint32_t rangePassesSkipped_ = 0;  // passes left for another field, the field key pressed
  bool quitPending_ = false;  // quit after the full-size frame that replaces a reduced last one
  double frameMs_ = 0, renderMs_ = 0, fragmentsPerPixel_ = 0;
  bool overlay_ = true;
  bool legend_ = false;  // drawn into the image, so into screenshots too (render --legend's)
  // --fps: when the step shown last changed, the time spent holding steps back, and the shortest
  // time a step was shown while playing (rank 0).
  using Clock = std::chrono::steady_clock;
  std::optional<Clock::time_point> stepSince_;
  double paceWaitMs_ = 0;
  StateWaits stateWaits_;  // this rank's
  std::optional<double> shortestPlayedStepMs_;
};

Viewer::Viewer(const app::RenderJob& job, const ViewOptions& options, comm::Communicator& comm)
    : job_(job), options_(options), comm_(comm), overlay_(options.overlay), legend_(job.legend) {
  if (options.frames < 0) throw Error("--frames: ", options.frames, " is negative");
  if (options.interactiveScale < 1 || options.interactiveScale > 16)
    throw Error("--interactive-scale: ", options.interactiveScale, " is not in 1 .. 16");
  if (!(options.fps >= 0) || !std::isfinite(options.fps))
    throw Error("--fps: ", options.fps, " is not a positive number of steps a second");
  if (options.headless && options.frames == 0 && options.script.empty())
    throw Error("--headless needs --frames or --script (there is no window to take input from)");
  vk::ContextOptions vo = app::contextOptions(job);
  if (root()) {
    // Input and window problems show before minutes of loading.
    if (!options.script.empty()) script_ = Script::load(options.script);
    window_ = std::make_unique<Window>(job.width, job.height, "shellmarch view - " + job.mesh,
                                       options.headless);
    vo.instanceExtensions = window_->instanceExtensions();
    vo.swapchain = true;
  }
  scene_ = std::make_unique<ViewScene>(job, vo, comm);
  if (root()) {
    presenter_ = std::make_unique<Presenter>(*window_, scene_->context(), job.background);
    input_ = std::make_unique<InputHandler>(scene_->homeCamera(), scene_->choices());
    early_ = std::make_unique<EarlyInput>(*window_, script_);
    scene_->setInterrupt([this] { return early_->interruptArrived(); });
  }
  state_ = scene_->initialState(job.width, job.height, options.play);
  log::info("view: loaded in ", scene_->loadSeconds(), " s, prepared in ", scene_->prepareSeconds(),
            " s");
}

void Viewer::run() {
  for (;;) {
    Timer frameTimer;
    if (root()) gatherInput();
    // Patiently: the other ranks may wait here long, while rank 0 waits for input or paces play.
    const Timer wait;
    const double cpu = threadCpuMs();
    comm_.broadcastPatiently(&state_, sizeof state_, 0);
    stateWaits_.ms += wait.ms();
    stateWaits_.cpuMs += threadCpuMs() - cpu;
    if (state_.quit) break;
    render::FrameResult frame;
    try {
      frame = scene_->render(state_, std::move(sparePixels_));
    } catch (const RangePassStopped& e) {  // on every rank
      if (e.why == PassInterrupt::FieldChange) {
        ++rangePassesSkipped_;  // the key is among the next frame's input
        continue;
      }
      rangePassStopped_ = true;
      break;
    }
    const uint64_t fragments = comm::sumOf(comm_, uint64_t(frame.fragments));
    if (root()) {
      renderMs_ = frame.timings.totalMs;
      show(frame, fragments);
    }
    ++state_.frame;
    frameMs_ = frameTimer.ms();
  }
  finish();
}

void Viewer::gatherInput() {
  const scene::Camera before = state_.camera();
  std::vector<InputEvent> events;
  const bool scripted = early_->takeFrame(events);
  const int32_t step = state_.step;
  const bool playing = state_.playing;
  applyEvents(events);
  // Nothing to draw into while minimised: wait for the window to come back.
  auto [w, h] = window_->framebufferSize();
  while ((w <= 0 || h <= 0) && !state_.quit && !window_->closeRequested()) {
    window_->wait(0.1);
    window_->poll(events);
    applyEvents(events);
    std::tie(w, h) = window_->framebufferSize();
  }
  state_.width = std::min(w, 16384);
  state_.height = std::min(h, 16384);
  if (window_->closeRequested()) state_.quit = 1;
  if (options_.frames > 0 && state_.frame >= uint32_t(options_.frames)) state_.quit = 1;
  // Headless, a finished script is the end (there is no other input).
  if (!scripted && window_->headless() && options_.frames == 0) state_.quit = 1;
  // Playing, each frame after the first shows the next step, unless input picked one.
  if (playing && state_.playing && state_.step == step && state_.frame > 0 && !state_.quit &&
      paceStep(step)) {
    const Clock::time_point now = Clock::now();
    if (stepSince_) {
      const double shown = std::chrono::duration<double, std::milli>(now - *stepSince_).count();
      shortestPlayedStepMs_ = std::min(shortestPlayedStepMs_.value_or(shown), shown);
    }
    ++state_.step;
    stepSince_ = now;
  } else if (state_.step != step || !stepSince_) {
    stepSince_ = Clock::now();
  }
  chooseRenderScale(before);
}

// While the camera moves (a drag, the wheel), frames render small, and the first frame without
// motion at full size. A screenshot is always full size, and so is the last frame: a session that
// ends on a reduced frame shows that frame once more at full size before it quits.
void Viewer::chooseRenderScale(const scene::Camera& before) {
  const scene::Camera now = state_.camera();
  const bool moved = now.eye != before.eye || now.at != before.at || now.up != before.up ||
                     now.fovyDeg != before.fovyDeg || now.parallel != before.parallel ||
                     now.parallelScale != before.parallelScale;
  if (quitPending_) state_.quit = 1;
  if (state_.quit && framesShown_ > 0 && shownState_.renderScale > 1) {
    const uint32_t frame = state_.frame;
    state_ = shownState_;
    state_.frame = frame;
    state_.quit = 0;
    quitPending_ = true;
  }
  state_.renderScale = moved && !state_.quit && !quitPending_ && local_.screenshots.empty()
                           ? options_.interactiveScale
                           : 1;
}

// With --fps F a step stays on screen 1/F s at least before play moves on. The wait keeps taking
// input, so that a key may pause, pick a step or quit meanwhile; returns whether play may advance
// from `step` now.
bool Viewer::paceStep(int32_t step) {
  if (!(options_.fps > 0) || !stepSince_) return true;
  const Clock::time_point due =
      *stepSince_ + std::chrono::duration_cast<Clock::duration>(
                        std::chrono::duration<double>(1.0 / options_.fps));
  const Clock::time_point start = Clock::now();
  for (Clock::time_point now = start; now < due; now = Clock::now()) {
    const double left = std::chrono::duration<double>(due - now).count();
    if (window_->headless())
      std::this_thread::sleep_for(due - now);
    else
      window_->wait(left);
    std::vector<InputEvent> events;
    window_->poll(events);
    applyEvents(events);
    if (window_->closeRequested()) state_.quit = 1;
    if (!state_.playing || state_.step != step || state_.quit) break;
  }
  paceWaitMs_ += std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  return state_.playing && state_.step == step && !state_.quit;
}

void Viewer::applyEvents(std::vector<InputEvent>& events) {
  for (const InputEvent& e : events) input_->apply(e, state_, local_);
  events.clear();
  if (local_.resizeWidth > 0) window_->requestSize(local_.resizeWidth, local_.resizeHeight);
  if (local_.toggleOverlay) overlay_ = !overlay_;
  if (local_.toggleLegend) legend_ = !legend_;
  if (local_.help) std::fputs(controlsHelp().c_str(), stderr);
  local_.resizeWidth = local_.resizeHeight = 0;
  local_.toggleOverlay = local_.toggleLegend = local_.help = false;
}

void Viewer::show(render::FrameResult& frame, uint64_t fragments) {
  uint64_t covered = 0;
  for (const glm::vec4& p : frame.pixels) covered += p.a > 0.0f;
  shownState_ = state_;
  sparePixels_ = std::move(lastPixels_);  // the next frame's storage
  lastWidth_ = state_.width;
  lastHeight_ = state_.height;
  if (state_.renderScale > 1) {
    // Into the frame before's storage; the small frame's becomes the next frame's: moving
    // allocates nothing frame after frame.
    ++reducedFrames_;
    lastPixels_ = std::move(sparePixels_);
    enlarge(frame.pixels, renderWidth(state_), renderHeight(state_), lastWidth_, lastHeight_,
            lastPixels_);
    sparePixels_ = std::move(frame.pixels);
  } else {
    lastPixels_ = std::move(frame.pixels);
  }
  if (legend_) {
    scene::Image img;
    img.width = lastWidth_;
    img.height = lastHeight_;
    img.pixels = std::move(lastPixels_);
    scene::drawLegend(img, scene_->settings().transferFunction, scene_->field().name,
                      job_.background);
    lastPixels_ = std::move(img.pixels);
  }
  fragmentsPerPixel_ = covered ? double(fragments) / double(covered) : 0.0;
  presenter_->show(lastPixels_, lastWidth_, lastHeight_,
                   overlay_ ? overlayLines() : std::vector<std::string>{});
  ++framesShown_;
  window_->setTitle("shellmarch view | " + job_.mesh + " | " + scene_->field().name + " step " +
                    std::to_string(state_.step) + " | " +
                    formatNumber("%.1f ms", frameMs_ > 0 ? frameMs_ : renderMs_) + " | " +
                    formatNumber("%.2f fragments/pixel", fragmentsPerPixel_));
  writeScreenshots();
}

// Frame time is the previous frame's, input to present: this one is not presented yet. Fragments
// per pixel count every rank's fragments over the pixels the composited image covers.
std::vector<std::string> Viewer::overlayLines() const {
  const FieldInfo& f = scene_->field();
  std::vector<std::string> lines;
  lines.push_back(formatNumber("frame %.1f ms", frameMs_ > 0 ? frameMs_ : renderMs_) +
                  formatNumber(" (render %.1f ms)", renderMs_));
  lines.push_back(formatNumber("%.2f fragments/pixel", fragmentsPerPixel_));
  lines.push_back(f.name + " step " + std::to_string(state_.step) + "/" + std::to_string(f.steps) +
                  (!state_.playing    ? std::string("  ")
                   : options_.fps > 0 ? formatNumber(" playing, at most %g/s  ", options_.fps)
                                      : std::string(" playing  ")) +
                  scene_->choices().colormaps[size_t(state_.colormap)]);
  lines.push_back(
      formatNumber("opacity x%.3g", state_.opacityScale) + formatNumber("  dt %.3g", state_.dt) +
      (scene_->settings().transferFunction.scale == scene::ScalarScale::Log ? "  log scale" : ""));
  if (state_.renderScale > 1)
    lines.push_back(formatNumber("moving: 1/%g size", double(state_.renderScale)));
  if (state_.cut) {
    const auto short3 = [](const glm::dvec3& v, const char* f) {
      return formatNumber(f, v.x) + "," + formatNumber(f, v.y) + "," + formatNumber(f, v.z);
    };
    lines.push_back("cut at " + short3(state_.cutPoint, "%.3g") + " keeps " +
                    short3(state_.cutNormal, "%.2f"));
  }
  return lines;
}

void Viewer::writeScreenshots() {
  if (lastPixels_.empty() || local_.screenshots.empty()) return;
  scene::Image img(lastWidth_, lastHeight_);
  img.pixels = lastPixels_;
  for (const std::string& requested : local_.screenshots) {
    const std::string path =
        requested.empty() ? numberedPath(options_.screenshot, state_.frame) : requested;
    scene::writePng(path, img, job_.background);  // atomic: a viewer of the file never sees half
    log::info("view: screenshot ", path);
  }
  local_.screenshots.clear();
}

Viewer::StateWaits Viewer::otherRanksStateWaits() {
  return {comm::maxOf(comm_, root() ? 0.0 : stateWaits_.ms),
          comm::maxOf(comm_, root() ? 0.0 : stateWaits_.cpuMs)};
}

nlohmann::json Viewer::report(uint64_t errors, const StateWaits& waits) const {
  const FieldInfo& f = scene_->field();
  const scene::Camera& home = scene_->homeCamera();
  const auto& tf = scene_->settings().transferFunction;
  const std::string colormap = scene_->choices().colormaps[size_t(state_.colormap)];
  nlohmann::json j;
  j["frames"] = framesShown_;
  j["reduced_frames"] = reducedFrames_;
  j["interactive_scale"] = options_.interactiveScale;
  j["ranks"] = comm_.size();
  j["size"] = {lastWidth_, lastHeight_};
  j["eye"] = {state_.eye.x, state_.eye.y, state_.eye.z};
  j["at"] = {state_.at.x, state_.at.y, state_.at.z};
  j["up"] = {state_.up.x, state_.up.y, state_.up.z};
  j["fovy"] = state_.fovyDeg;
  j["parallel"] = state_.parallel != 0;
  j["parallel_scale"] = state_.parallelScale;
  j["field"] = f.name;
  j["time"] = state_.step;
  j["playing"] = bool(state_.playing);
  j["fps_cap"] = options_.fps;
  j["pace_wait_ms"] = paceWaitMs_;
  j["other_ranks_state_wait_ms"] = waits.ms;
  j["other_ranks_state_wait_cpu_ms"] = waits.cpuMs;
  j["shortest_played_step_ms"] =
      shortestPlayedStepMs_ ? nlohmann::json(*shortestPlayedStepMs_) : nlohmann::json(nullptr);
  j["colormap"] = colormap;
  j["range"] = {f.range.first, f.range.second};
  j["opacity_scale"] = state_.opacityScale;
  j["step"] = state_.dt;
  j["unit_distance"] = tf.unitDistance;
  j["fragments_per_pixel"] = fragmentsPerPixel_;
  j["presented"] = presenter_->presented();
  j["swapchain_rebuilds"] = presenter_->swapchainRebuilds();
  j["pipelines_built"] = scene_->pipelinesBuilt();
  j["validation_errors"] = errors;
  j["home"] = {{"eye", {home.eye.x, home.eye.y, home.eye.z}},
               {"at", {home.at.x, home.at.y, home.at.z}}};
  j["geometry_builds"] = scene_->gpu().geometryBuilds();
  j["scalar_uploads"] = scene_->gpu().scalarUploads();
  j["prefetched_steps"] = scene_->prefetchedSteps();
  j["stopped_reads"] = stoppedReads_;  // over all ranks
  j["range_pass_stopped"] = rangePassStopped_;
  j["range_passes_skipped"] = rangePassesSkipped_;
  j["range_steps_read"] = scene_->rangeStepsRead();  // rank 0's
  j["scalar_wait_ms"] = scene_->scalarWaitMs();
  j["scalar_load_ms"] = scene_->scalarLoadMs();
  // What `shellmarch render` needs, besides the data options given to view, for this frame.
  static const std::vector<scene::OpacityPoint> kNone;
  const std::vector<scene::OpacityPoint>& points = state_.field == 0 ? job_.opacityPoints : kNone;
  j["render_args"] = renderArgs(state_, lastWidth_, lastHeight_,
                                {f, colormap, tf, points, scene_->settings().clipPlanes, legend_,
                                 scene_->settings().integration == render::Integration::Sampled});
  j["legend"] = legend_;
  j["cut"] =
      state_.cut
          ? nlohmann::json{{"point", {state_.cutPoint.x, state_.cutPoint.y, state_.cutPoint.z}},
                           {"normal", {state_.cutNormal.x, state_.cutNormal.y, state_.cutNormal.z}}}
          : nlohmann::json(nullptr);
  return j;
}

void Viewer::finish() {
  // First, so that closing never waits for a step that will not be shown to be read.
  scene_->stopReadAhead();
  if (root()) {
    if (!options_.screenshot.empty()) local_.screenshots.push_back(options_.screenshot);
    if (lastPixels_.empty() && !local_.screenshots.empty())
      log::warning("view: no frame was rendered, so no screenshot was written");
    writeScreenshots();
  }
  const uint64_t errors = comm::sumOf(comm_, scene_->context().validationErrors());
  stoppedReads_ = comm::sumOf(comm_, scene_->stoppedReads());
  const StateWaits waits = otherRanksStateWaits();
  if (root() && !options_.saveCamera.empty()) {
    scene::writeCameraFile(options_.saveCamera, state_.camera());
    log::info("view: camera written to ", options_.saveCamera);
  }
  if (root() && options_.printCamera) {
    std::printf("%s\n", report(errors, waits).dump().c_str());
    std::fflush(stdout);
  }
  if (errors) throw Error("the Vulkan validation layer reported ", errors, " error(s)");
}

}  // namespace

void runView(const app::RenderJob& job, const ViewOptions& options, comm::Communicator& comm) {
  Viewer viewer(job, options, comm);
  viewer.run();
}

}  // namespace sm::view
