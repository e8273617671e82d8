// One rank's side of the viewer: its share of the data on the GPU, and the compositor and renderer
// for the image sizes in use. render() first makes the GPU side match the broadcast state: a new
// time step or field uploads scalars only, a new size builds a compositor and renderer (sharing
// the pipelines; the last two sizes are kept, the window's and the interactive one's), a new
// colour map, opacity or step only changes the frame's settings. While the state plays, the
// next step is read and uploaded on a thread of its own while the frame renders.
//
// Every rank calls render() with the same state, because a new field needs collectives (its
// steps and range over all ranks) and compositing is collective.
#pragma once

#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "comm/reductions.h"
#include "pipeline/rank_pipeline.h"
#include "pipeline/rank_share.h"
#include "pipeline/render_options.h"
#include "pipeline/step_loads.h"
#include "pipeline/step_source.h"
#include "render/renderer.h"
#include "session/rank_session.h"
#include "viewer/view_state.h"

namespace sm::view {

struct FieldInfo {
  std::string name;
  uint64_t steps = 1;                         // most steps on any rank
  std::pair<double, double> range{0.0, 1.0};  // over all its steps, all ranks
};

// Thrown by ViewScene::render on every rank when its interrupt check stopped a range pass.
struct RangePassStopped : std::exception {
  PassInterrupt why = PassInterrupt::Quit;
  explicit RangePassStopped(PassInterrupt w) : why(w) {}
  const char* what() const noexcept override { return "a field's range pass was stopped"; }
};

class ViewScene {
 public:
  // Loads and prepares this rank's share and uploads it. `vo` are the Context options (rank 0
  // adds what presentation needs).
  ViewScene(const app::RenderJob& job, const vk::ContextOptions& vo, comm::Communicator& comm);
  ~ViewScene();

  const ViewChoices& choices() const { return choices_; }
  // The state of the first frame (the job's camera, field, step, colour map, sampling).
  ViewState initialState(int width, int height, bool playing) const;
  const scene::Camera& homeCamera() const { return home_; }

  // Brings the GPU side in line with `state` (normalising its step into the field's steps) and
  // renders; collective.
  // `reuse`: storage for the image (Renderer::render).
  render::FrameResult render(ViewState& state, std::vector<glm::vec4> reuse = {});

  const vk::Context& context() const { return session_->context(); }
  const render::GpuScene& gpu() const { return session_->scene(); }
  // Pipelines built for this scene's frames so far (a resize builds none).
  uint64_t pipelinesBuilt() const { return session_->pipelinesBuilt(); }
  const FieldInfo& field() const { return field_; }
  const render::RenderSettings& settings() const { return settings_; }
  // Steps whose scalars a prefetch had loaded when they were shown, and what loading the steps
  // shown cost, the first frame's included: the frames' wait for their scalars, and reading and
  // uploading them on whichever thread did it (ms, summed).
  uint64_t prefetchedSteps() const { return prefetchedSteps_; }
  double scalarWaitMs() const { return scalarWaitMs_; }
  double scalarLoadMs() const { return scalarLoadMs_; }
  // Stops a step read ahead (closing); how many reads ahead were stopped before they ended.
  void stopReadAhead() { loads_->discard(); }
  uint64_t stoppedReads() const { return loads_->stoppedReads(); }
  // Asked before each step a new field's range pass reads (every step of the field, on this
  // thread): once it says stop on any rank, render() throws RangePassStopped on every rank
  // (collective), with the strongest reason any rank gave. Rank 0 passes the window's close and
  // field key; the others need none. The field stays as it was before the pass.
  void setInterrupt(std::function<PassInterrupt()> interrupt) { interrupt_ = std::move(interrupt); }
  uint64_t rangeStepsRead() const { return rangeStepsRead_; }
  double loadSeconds() const { return loadSeconds_; }
  double prepareSeconds() const { return prepareSeconds_; }

 private:
  void selectField(int index);
  FieldInfo describeField(const std::string& name, std::optional<std::pair<double, double>> range);
  scene::ScalarScale scaleFor(const ViewState& state, const FieldInfo& f) const;
  void warnIfLinearInstead(const ViewState& state);
  void applyState(ViewState& state);
  void applyStep(ViewState& state);

  const app::RenderJob& job_;
  comm::Communicator& comm_;
  app::RankShare share_;
  std::unique_ptr<app::StepSource> source_;  // the shown step of a field, from share_ or its file
  app::PreparedShare prepared_;
  ViewChoices choices_;
  scene::Camera home_;
  // "Finer step" stops here: a hundredth of the starting step keeps frames interactive.
  double finestInteractiveStep_ = 0.0;
  double loadSeconds_ = 0, prepareSeconds_ = 0;
  // The device, the scene and a compositor and renderer for each of the two image sizes last
  // used (interaction at a reduced size, the still frames between).
  std::unique_ptr<session::RankSession> session_;
  std::unique_ptr<app::StepLoads> loads_;  // after session_: its prefetch thread writes there
  uint64_t prefetchedSteps_ = 0;
  double scalarWaitMs_ = 0, scalarLoadMs_ = 0;
  render::RenderSettings settings_;
  FieldInfo field_;
  std::vector<std::optional<FieldInfo>> fields_;  // choices_.fields', once selected
  int fieldIndex_ = -1, step_ = -1, colormap_ = -1;
  int tableField_ = 0;  // the field the transfer function's opacity was made for
  scene::ScalarScale tableScale_ = scene::ScalarScale::Linear;  // and the scale
  std::set<int> linearWarned_;  // fields told that a log scale needs a positive range
  std::function<PassInterrupt()> interrupt_;
  uint64_t rangeStepsRead_ = 0;
};

// The time step --time names: one index (the viewer shows one step at a time).
int parseViewStep(const std::string& time);

}  // namespace sm::view
