#include "viewer/view_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <utility>

#include "common/error.h"
#include "common/log.h"
#include "common/timer.h"
#include "pipeline/render_setup.h"
#include "render/step_limits.h"

namespace sm::view {
namespace {

// Rank 0's list, on every rank: a rank without clusters may have read no fields at all.
std::vector<std::string> agreedFieldNames(const mesh::UnstructuredMesh& m, const std::string& first,
                                          comm::Communicator& comm) {
  std::vector<std::string> names;
  if (comm.rank() == 0) {
    names.push_back(first);
    for (const auto& f : m.fields)
      if (f.name != first) names.push_back(f.name);
  }
  return comm::broadcastNames(comm, std::move(names));
}

std::vector<std::string> colormapChoices(const std::string& first) {
  std::vector<std::string> all{first};
  for (const auto& n : scene::builtinColormapNames())
    if (n != first) all.push_back(n);
  return all;
}

// Names the file's cell data among the fields to read, after its point fields, where each step is
// read when shown (app::streamsCellData): a solver's cell-centred output (Fluent, STAR-CCM+) is
// then browsed like point data. Where cell data would be loaded whole (every step of every array
// in memory, e.g. one .vtu split among ranks), only --field names it. A name that is also point
// data (foamToVTK writes both) stays the point data. Rank 0 reads the headers for every rank.
void withCellData(const std::string& path, app::ShareOptions& share, comm::Communicator& comm) {
  if (!app::streamsCellData(path, share, comm.size())) return;  // the same on every rank
  app::HeaderFields h = app::listHeaderFields(path, share.read, comm);
  if (h.cells.empty()) return;
  share.read.fields = std::move(h.points);
  share.read.fields.insert(share.read.fields.end(), h.cells.begin(), h.cells.end());
  share.cellData = true;
}

int wrap(int value, uint64_t count) {
  const int n = int(std::max<uint64_t>(count, 1));
  return ((value % n) + n) % n;
}

}  // namespace

int parseViewStep(const std::string& time) {
  char* end = nullptr;
  long long t = std::strtoll(time.c_str(), &end, 10);
  if (time.empty() || *end || t < 0 || t > 1 << 30)
    throw Error("--time: '", time, "' is not a step index (view shows one step at a time)");
  return int(t);
}

ViewScene::ViewScene(const app::RenderJob& job, const vk::ContextOptions& vo,
                     comm::Communicator& comm)
    : job_(job), comm_(comm) {
  session::checkRequest(app::frameRequest(job));
  const int firstStep = parseViewStep(job.time);
  Timer load;
  // The viewer cycles through every point field as a file holds it (vectors as magnitudes), then
  // its cell data where that is streamed (withCellData). A component ("v[1]") or cell data named
  // by --field is the one field shown.
  app::ShareOptions share = job.share;
  // Steps are read from the file when shown (as `render --time all` reads them), so that a long
  // series holds one step per field in memory, not every step of every field.
  share.streamSteps = true;
  io::ReadOptions named = share.read;
  named.fields = {job.field};
  if (!job.field.empty()) {
    share.cellData = app::fieldsAreCellData(job.mesh, named, comm);
    if (job.field.back() == ']' || *share.cellData) share.read = named;
  }
  if (share.read.fields.empty()) withCellData(job.mesh, share, comm);
  share_ = app::loadRankShare(job.mesh, share, comm);
  source_ = std::make_unique<app::StepSource>(job.mesh, share_, comm);  // before preparation
  loadSeconds_ = load.seconds();
  choices_.fields = agreedFieldNames(share_.mesh, app::resolveField(job, share_.mesh, comm), comm);
  choices_.colormaps = colormapChoices(job.colormap);
  choices_.cutAvailable = job.clipPlanes.size() < size_t(scene::kMaxClipPlanes);
  fields_.resize(choices_.fields.size());
  selectField(0);
  settings_ = app::makeSettings(job, share_, field_.name, field_.range);
  colormap_ = 0;
  home_ = settings_.camera;
  finestInteractiveStep_ = settings_.dt / 100.0;
  if (uint64_t(firstStep) >= field_.steps)
    throw Error("--time: field '", field_.name, "' has ", field_.steps, " time steps (0 .. ",
                field_.steps - 1, "), not step ", firstStep);
  Timer prep;
  prepared_ = app::prepareShare(share_, prep::PrepOptions{job.compact}, job.cacheDir, comm.rank(),
                                comm.size());
  prepareSeconds_ = prep.seconds();
  session_ = std::make_unique<session::RankSession>(
      vo, comm::withPeers(comm_), session::SessionOptions{job.lists, vk::Tracer::Auto, 2});
  session_->setScene(prepared_.rank, std::move(prepared_.rank.positions));
  loads_ = std::make_unique<app::StepLoads>(*source_, prepared_.rank, session_->scene());
}

ViewScene::~ViewScene() = default;

ViewState ViewScene::initialState(int width, int height, bool playing) const {
  ViewState s;
  s.setCamera(home_);
  s.opacityScale = job_.opacityScale;
  s.dt = settings_.dt;
  s.width = width;
  s.height = height;
  s.step = parseViewStep(job_.time);
  s.playing = playing;
  s.logScale = job_.logScale ? 1 : 0;
  return s;
}

void ViewScene::selectField(int index) {
  std::optional<FieldInfo>& known = fields_.at(size_t(index));
  if (!known)  // may throw RangePassStopped: the field shown stays as it was
    known = describeField(choices_.fields[size_t(index)], index == 0 ? job_.range : std::nullopt);
  fieldIndex_ = index;
  field_ = *known;
  settings_.transferFunction.lo = field_.range.first;
  settings_.transferFunction.hi = field_.range.second;
  step_ = -1;  // scalars of the new field are uploaded by applyState
}

// The log scale (--log-scale, the g key) applies to the fields whose range is positive; the others
// show on a linear scale (with --log-scale, the first field's range was checked at start, as
// render checks it).
scene::ScalarScale ViewScene::scaleFor(const ViewState& state, const FieldInfo& f) const {
  return state.logScale && f.range.first > 0 ? scene::ScalarScale::Log : scene::ScalarScale::Linear;
}

// A log scale asked for (the g key) on a field it cannot show says so, once per field, rather
// than leave the key looking broken.
void ViewScene::warnIfLinearInstead(const ViewState& state) {
  if (!state.logScale || field_.range.first > 0 || comm_.rank() != 0) return;
  if (!linearWarned_.insert(fieldIndex_).second) return;
  log::warning("view: field '", field_.name, "' has the range ", field_.range.first, " .. ",
               field_.range.second,
               "; a log scale needs a positive one, so it is shown on a linear scale");
}

// Collective, as every rank selects the same fields in the same order; kept per field, so that
// coming back to one does not read its steps again. Whether this rank has points comes from the
// step source: after the first field, preparation has taken them out of the share's mesh (which
// once made every later field look like one step on every rank).
FieldInfo ViewScene::describeField(const std::string& name,
                                   std::optional<std::pair<double, double>> range) {
  FieldInfo f;
  f.name = name;
  f.steps = std::max<uint64_t>(
      app::agreedStepCount(job_.mesh, name, source_->numSteps(name), source_->hasPoints(), comm_),
      1);
  if (range) {
    f.range = *range;
    return f;
  }
  // Over every step, so that colours mean the same while stepping through time: each step is
  // read once, one at a time. A field with no finite value shows as empty, not as an error, so
  // that cycling through fields goes on.
  mesh::Range r;
  for (uint64_t step = 0; step < f.steps; ++step) {
    const double why = comm::maxOf(comm_, interrupt_ ? double(interrupt_()) : 0.0);
    if (why > 0.0) throw RangePassStopped(PassInterrupt(int(why)));
    r.extend(source_->range(name, step));
    ++rangeStepsRead_;
  }
  const double lo = comm::minOf(comm_, r.empty ? INFINITY : r.lo),
               hi = comm::maxOf(comm_, r.empty ? -INFINITY : r.hi);
  if (lo <= hi) f.range = {lo, hi};
  return f;
}

// The range pass of a new field reads steps on this thread: no prefetch may read beside it.
void ViewScene::applyStep(ViewState& state) {
  if (state.field != fieldIndex_) {
    loads_->discard();
    selectField(state.field);
  }
  state.step = wrap(state.step, field_.steps);
  if (state.step != step_) {
    const render::ScalarSwitch s = loads_->loadFor(field_.name, uint64_t(state.step));
    prefetchedSteps_ += s.prefetched;
    scalarWaitMs_ += s.waitMs;
    scalarLoadMs_ += s.loadMs + s.uploadMs;
    step_ = state.step;
  }
  // Every rank plays the same broadcast state, so the collective half of a streamed cell
  // field's prefetch (loadFor) comes at the same frame on every rank.
  if (state.playing && field_.steps > 1)
    loads_->prefetch(field_.name, uint64_t(wrap(state.step + 1, field_.steps)));
}

void ViewScene::applyState(ViewState& state) {
  applyStep(state);
  // The table follows the colour map and, with --opacity, the field: the points are values of
  // the first field, and the others keep their colour map's opacity.
  const bool points = !job_.opacityPoints.empty();
  // Opacity points sit at each entry's value, which the scale decides.
  const scene::ScalarScale scale = scaleFor(state, field_);
  warnIfLinearInstead(state);
  if (state.colormap != colormap_ ||
      (points && (fieldIndex_ != tableField_ || scale != tableScale_))) {
    session::FrameRequest r = app::frameRequest(job_);  // --nan-color holds for every map
    r.colormap = choices_.colormaps[size_t(state.colormap)];
    r.logScale = scale == scene::ScalarScale::Log;  // only over a positive range (scaleFor)
    if (fieldIndex_ != 0) r.opacityPoints.clear();
    const double unit = settings_.transferFunction.unitDistance;
    settings_.transferFunction = session::makeTransferFunction(r, field_.name, field_.range);
    settings_.transferFunction.unitDistance = unit;
    colormap_ = state.colormap;
    tableField_ = fieldIndex_;
    tableScale_ = scale;
  }
  settings_.transferFunction.scale = scale;
  settings_.transferFunction.opacityScale = state.opacityScale;
  settings_.camera = state.camera();
  settings_.clipPlanes = job_.clipPlanes;
  if (state.cut) settings_.clipPlanes.push_back(state.cutPlane());
  // "Finer step" stops at a hundredth of the starting step, and zooming far out at the finest
  // step that float positions along a ray resolve (render::checkStep); "coarser step" at the
  // data's diagonal, past which most rays take no sample (render::checkStepNotBeyondData).
  state.dt = std::max({state.dt, finestInteractiveStep_,
                       render::finestStep(settings_.camera.eye, share_.wholeBounds)});
  if (!share_.wholeBounds.empty) state.dt = std::min(state.dt, share_.wholeBounds.diagonal());
  settings_.dt = state.dt;
  settings_.width = renderWidth(state);
  settings_.height = renderHeight(state);
}

render::FrameResult ViewScene::render(ViewState& state, std::vector<glm::vec4> reuse) {
  applyState(state);
  return session_->render(settings_, std::move(reuse));
}

}  // namespace sm::view
