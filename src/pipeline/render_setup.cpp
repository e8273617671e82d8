#include "pipeline/render_setup.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/error.h"
#include "common/log.h"
#include "io/mesh_io.h"
#include "render/frame_defaults.h"

namespace sm::app {

void checkImageSize(const RenderJob& job) {
  if (job.width <= 0 || job.height <= 0 || job.width > 16384 || job.height > 16384)
    throw Error("--size: ", job.width, "x", job.height,
                " is not a usable image size (1 .. 16384 per side)");
}

std::string resolveField(const RenderJob& job, const mesh::UnstructuredMesh& m,
                         comm::Communicator& comm) {
  if (!job.field.empty()) return job.field;
  // Rank 0's first field, on every rank: a rank without clusters has read no fields, and ranks
  // left to choose could each take a different one.
  std::string name;
  if (comm.rank() == 0) {
    if (m.fields.empty())
      throw Error(job.mesh, ": has no point fields to render", mesh::cellArrayHint(m.cellArrays));
    name = m.fields.front().name;
    log::info("--field not given: rendering '", name, "'");
  }
  return comm::broadcastString(comm, std::move(name));
}

HeaderFields listHeaderFields(const std::string& path, const io::ReadOptions& read,
                              comm::Communicator& comm) {
  HeaderFields h;
  if (comm.rank() == 0) {
    try {
      std::vector<std::string> cells = io::listCellData(path, read);
      // The first piece alone: whether the pieces agree is the load's to say (on several ranks,
      // naming the ranks and their pieces).
      io::ReadOptions first = read;
      first.pieces = {0};
      if (!cells.empty())
        for (const io::FieldStepCount& f : io::listFieldSteps(path, first))
          h.points.push_back(f.name);
      for (std::string& c : cells)
        if (std::find(h.points.begin(), h.points.end(), c) == h.points.end())
          h.cells.push_back(std::move(c));
    } catch (const Error&) {
      h = {};  // a file these headers do not describe is the load's to refuse, in its words
    }
  }
  h.points = comm::broadcastNames(comm, std::move(h.points));
  h.cells = comm::broadcastNames(comm, std::move(h.cells));
  return h;
}

std::string defaultCellField(const RenderJob& job, comm::Communicator& comm) {
  if (!job.field.empty()) return {};
  const HeaderFields h = listHeaderFields(job.mesh, job.share.read, comm);
  if (!h.points.empty() || h.cells.empty()) return {};
  if (comm.rank() == 0)
    log::info("--field not given: rendering cell data '", h.cells.front(), "' (", job.mesh,
              " has no point fields)");
  return h.cells.front();
}

uint64_t agreedStepCount(const std::string& path, const std::string& field, uint64_t mine,
                         bool hasPoints, comm::Communicator& comm) {
  const double lo = comm::minOf(comm, hasPoints ? double(mine) : INFINITY);
  const double hi = comm::maxOf(comm, hasPoints ? double(mine) : -INFINITY);
  if (!(lo <= hi)) return 0;
  if (lo == hi) return uint64_t(hi);
  auto firstRankWith = [&](double count) {
    return int(
        comm::minOf(comm, hasPoints && double(mine) == count ? double(comm.rank()) : INFINITY));
  };
  const int rankLo = firstRankWith(lo), rankHi = firstRankWith(hi);
  auto steps = [&](double n) { return concat(uint64_t(n), n == 1 ? " time step" : " time steps"); };
  const std::string fewer =
      lo == 0 ? concat("no field '", field, "'") : concat(steps(lo), " of field '", field, "'");
  throw FileError(path, "the pieces of rank ", rankLo, " have ", fewer, ", those of rank ", rankHi,
                  " ", steps(hi),
                  " (the pieces of one file must agree, as when one rank reads them all)");
}

scene::Camera makeCamera(const RenderJob& job, const mesh::Bounds& whole) {
  const double aspect = double(job.width) / job.height;
  scene::Camera c;
  if (!job.eye) {
    if (job.at || job.up) throw Error("--at and --up need --eye (or use --view)");
    c = scene::frameBounds(
        whole, scene::parseViewPreset(job.view), aspect, job.fovy,
        job.parallel ? scene::Projection::Parallel : scene::Projection::Perspective);
  } else {
    c.eye = *job.eye;
    c.at = job.at.value_or(whole.center());
    if (!job.at && c.eye == c.at)
      throw Error("--eye: ", c.eye.x, ",", c.eye.y, ",", c.eye.z,
                  " is the centre of the data, where the camera looks without --at: give --at");
    c.up = job.up.value_or(scene::defaultUp(c.at - c.eye));
    c.fovyDeg = job.fovy;
    c.parallel = job.parallel;
    c.parallelScale = scene::fitParallelScale(whole, aspect);
  }
  if (job.parallelScale) c.parallelScale = *job.parallelScale;
  return c;
}

void applyNanColor(const RenderJob& job, scene::TransferFunction& tf) {
  if (!job.nanColor) return;
  tf.nanColor = glm::vec3(*job.nanColor);
  tf.nanOpacity = job.nanColor->a;
}

render::RenderSettings makeSettings(const RenderJob& job, const RankShare& share,
                                    const std::string& field, std::pair<double, double> range) {
  render::RenderSettings s;
  s.width = job.width;
  s.height = job.height;
  s.camera = makeCamera(job, share.wholeBounds);
  s.transferFunction = scene::makeTransferFunction(job.colormap);
  s.transferFunction.lo = range.first;
  s.transferFunction.hi = range.second;
  if (job.logScale) {
    s.transferFunction.scale = scene::ScalarScale::Log;
    if (!(range.first > 0))
      throw Error("--log-scale: field '", field, "' has the range ", range.first, " .. ",
                  range.second,
                  ", and a log scale needs a positive one: give --range LO,HI with "
                  "0 < LO < HI");
  }
  if (!job.opacityPoints.empty())
    scene::setOpacityPoints(s.transferFunction, job.opacityPoints, "--opacity");
  applyNanColor(job, s.transferFunction);
  s.transferFunction.opacityScale = job.opacityScale;
  s.transferFunction.unitDistance =
      job.unitDistance.value_or(render::defaultUnitDistance(share.wholeBounds));
  s.dt = job.step.value_or(render::defaultStep(share.elementSize.mean(), share.wholeBounds));
  // Without --step the step comes from the mesh: a fault then lies with the mesh or the view,
  // not with an option the user did not give.
  if (!job.step && !(s.dt > 0))
    throw Error(job.mesh, ": every element has zero volume: there is no volume to render");
  if (const double finest = render::finestStep(s.camera.eye, share.wholeBounds);
      !job.step && s.dt < finest)
    throw Error("the default sample step ", s.dt,
                " (half the mean element size, at most the diagonal / 256) is finer than ",
                "float distances along a ray resolve this far from the data (up to ",
                finest * 0x1p24, "): move the eye closer or give --step of at least ", finest);
  // Checked here against the whole data set too, so that every rank refuses the step alike.
  render::checkStep(s.dt, s.camera.eye, share.wholeBounds);
  // Element-exact integration takes no samples (the step only bounds the pieces of non-linear
  // cells), so a step beyond the data is harmless there.
  if (job.integration == render::Integration::Sampled)
    render::checkStepNotBeyondData(s.dt, share.wholeBounds);
  s.earlyTermination = job.earlyTermination;
  s.integration = job.integration;
  s.shading = job.shading;
  s.clipPlanes = job.clipPlanes;
  s.allTypePipelines = job.allTypePipelines;
  if (!(s.transferFunction.unitDistance > 0)) throw Error("--unit-distance must be positive");
  if (!(job.opacityScale >= 0)) throw Error("--opacity-scale must not be negative");
  return s;
}

vk::ContextOptions contextOptions(const RenderJob& job) {
  vk::ContextOptions vo;
  vo.device = job.device;
  vo.tracer = job.tracer;
  vo.cacheDir = job.cacheDir;
  return vo;
}

}  // namespace sm::app
