#include "pipeline/render_setup.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/error.h"
#include "common/log.h"
#include "io/mesh_io.h"

namespace sm::app {

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

session::FrameRequest frameRequest(const RenderJob& job) {
  session::FrameRequest r;
  r.width = job.width;
  r.height = job.height;
  r.view = job.view;
  r.eye = job.eye;
  r.at = job.at;
  r.up = job.up;
  r.fovyDeg = job.fovy;
  r.parallel = job.parallel;
  r.parallelScale = job.parallelScale;
  r.colormap = job.colormap;
  r.opacityPoints = job.opacityPoints;
  r.logScale = job.logScale;
  r.nanColor = job.nanColor;
  r.opacityScale = job.opacityScale;
  r.unitDistance = job.unitDistance;
  r.step = job.step;
  r.integration = job.integration;
  r.earlyTermination = job.earlyTermination;
  r.shading = job.shading;
  r.clipPlanes = job.clipPlanes;
  r.allTypePipelines = job.allTypePipelines;
  return r;
}

session::DataExtent dataExtent(const RenderJob& job, const RankShare& share) {
  return {share.wholeBounds, share.elementSize.mean(), job.mesh};
}

render::RenderSettings makeSettings(const RenderJob& job, const RankShare& share,
                                    const std::string& field, std::pair<double, double> range) {
  return session::makeRenderSettings(frameRequest(job), dataExtent(job, share), field, range);
}

vk::ContextOptions contextOptions(const RenderJob& job) {
  vk::ContextOptions vo;
  vo.device = job.device;
  vo.tracer = job.tracer;
  vo.cacheDir = job.cacheDir;
  return vo;
}

}  // namespace sm::app
