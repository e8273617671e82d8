#include "app/render_job.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include <nlohmann/json.hpp>

#include "app/memory_advice.h"
#include "app/rank_pipeline.h"
#include "app/render_stats.h"
#include "common/error.h"
#include "common/fault_injection.h"
#include "common/log.h"
#include "common/timer.h"
#include "render/renderer.h"
#include "scene/image.h"
#include "vk/context.h"
#include "vk/vk_error.h"

namespace sm::app {
namespace {

std::string resolveField(const RenderJob& job, const mesh::UnstructuredMesh& m) {
  if (!job.field.empty()) return job.field;
  if (m.fields.empty()) throw Error(job.mesh, ": has no point fields to render");
  log::info("--field not given: rendering '", m.fields.front().name, "'");
  return m.fields.front().name;
}

std::vector<uint64_t> stepsToRender(const RenderJob& job, uint64_t available) {
  if (job.time == "all") {
    std::vector<uint64_t> all(std::max<uint64_t>(available, 1));
    for (uint64_t i = 0; i < all.size(); ++i) all[i] = i;
    return all;
  }
  char* end = nullptr;
  long long t = std::strtoll(job.time.c_str(), &end, 10);
  if (job.time.empty() || *end || t < 0) throw Error("--time: '", job.time, "' is not a step index or 'all'");
  return {uint64_t(t)};
}

// Range of the field over the steps to render, on every rank.
std::pair<double, double> globalRange(const mesh::UnstructuredMesh& m, const std::string& field,
                                      const std::vector<uint64_t>& steps, Collectives& coll) {
  mesh::Range r;
  if (const mesh::Field* f = m.findField(field))
    for (uint64_t s : steps) r.extend(mesh::fieldRange(*f, s));
  double lo = coll.min(r.empty ? INFINITY : r.lo), hi = coll.max(r.empty ? -INFINITY : r.hi);
  if (!(lo <= hi)) return {0.0, 1.0};
  return {lo, hi};
}

scene::Camera makeCamera(const RenderJob& job, const mesh::Bounds& whole) {
  if (!job.eye) {
    if (job.at || job.up) throw Error("--at and --up need --eye (or use --view)");
    return scene::frameBounds(whole, scene::parseViewPreset(job.view), double(job.width) / job.height, job.fovy);
  }
  scene::Camera c;
  c.eye = *job.eye;
  c.at = job.at.value_or(whole.center());
  c.up = job.up.value_or(glm::dvec3(0, 0, 1));
  c.fovyDeg = job.fovy;
  return c;
}

std::string framePath(const std::string& out, uint64_t step, bool sequence) {
  if (!sequence) return out;
  std::string stem = out, ext = ".png";
  if (auto dot = out.rfind('.'); dot != std::string::npos && out.find('/', dot) == std::string::npos) {
    stem = out.substr(0, dot);
    ext = out.substr(dot);
  }
  char num[16];
  std::snprintf(num, sizeof num, "_%04llu", (unsigned long long)step);
  return stem + num + ext;
}

}  // namespace

void runRender(const RenderJob& job, Collectives& coll) {
  if (job.width <= 0 || job.height <= 0 || job.width > 16384 || job.height > 16384)
    throw Error("--size: ", job.width, "x", job.height, " is not a usable image size (1 .. 16384 per side)");
  Timer total;
  RankShare share = loadRankShare(job.mesh, job.share, coll);
  const double loadSeconds = total.seconds();
  const std::string field = resolveField(job, share.mesh);
  const uint64_t available = share.mesh.findField(field) ? share.mesh.findField(field)->numSteps() : 1;
  const std::vector<uint64_t> steps = stepsToRender(job, coll.max(double(available)));
  auto [lo, hi] = job.range ? *job.range : globalRange(share.mesh, field, steps, coll);

  render::RenderSettings s;
  s.width = job.width;
  s.height = job.height;
  s.camera = makeCamera(job, share.wholeBounds);
  s.transferFunction = scene::makeTransferFunction(job.colormap);
  s.transferFunction.lo = lo;
  s.transferFunction.hi = hi;
  s.transferFunction.opacityScale = job.opacityScale;
  s.transferFunction.unitDistance = job.unitDistance.value_or(render::defaultUnitDistance(share.wholeBounds));
  s.dt = job.step.value_or(render::defaultStep(share.elementSize.mean()));
  s.earlyTermination = job.earlyTermination;
  if (!(s.transferFunction.unitDistance > 0)) throw Error("--unit-distance must be positive");
  if (!(job.opacityScale >= 0)) throw Error("--opacity-scale must not be negative");

  Timer prepTimer;
  PreparedShare prepared = prepareShare(share, prep::PrepOptions{job.compact}, job.cacheDir, coll.rank(), coll.size());
  const double prepSeconds = prepTimer.seconds();
  vk::ContextOptions vo;
  vo.device = job.device;
  vk::Context ctx(vo);
  // Out of device memory becomes a message that says what would fit, not a Vulkan call's name.
  std::unique_ptr<render::GpuScene> scene;
  try {
    scene = std::make_unique<render::GpuScene>(ctx, prepared.rank);
  } catch (const vk::DeviceMemoryError& e) {
    throw Error(sceneMemoryAdvice(e, ctx, prepared.rank, coll.size()));
  }
  render::GpuScene& gpu = *scene;
  try {
    comp::DeepCompositor compositor(ctx, coll.communicator(), job.width, job.height, job.lists);
    render::Renderer renderer(ctx, gpu, compositor);

    StatsReport report(job, coll);
    report.setSetup(loadSeconds, prepSeconds, prepared.fromCache, prepared.rank, gpu,
                    ctx.deviceName(), s);
    for (size_t i = 0; i < steps.size(); ++i) {
      const uint64_t step = steps[i];
      fault::atFrame(i);
      gpu.setScalars(fieldStep(share.mesh, prepared.rank, field, std::min(step, available - 1)));
      render::FrameResult frame = renderer.render(s);
      report.addFrame(step, frame, renderer);
      if (coll.rank() == 0) {
        scene::Image img(job.width, job.height);
        img.pixels = std::move(frame.pixels);
        scene::writePng(framePath(job.out, step, steps.size() > 1), img, job.background);
      }
    }
    report.finish(ctx.validationErrors());
  } catch (const vk::DeviceMemoryError& e) {
    throw Error(
        listMemoryAdvice(e, ctx, gpu.deviceBytes(), job.width, job.height, job.lists, coll.size()));
  }
}

}  // namespace sm::app
