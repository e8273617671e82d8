#include "app/render_job.h"

#include <cmath>
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "app/frame_extras.h"
#include "app/rank_pipeline.h"
#include "app/render_setup.h"
#include "app/render_stats.h"
#include "common/error.h"
#include "common/file_util.h"
#include "common/log.h"
#include "common/timer.h"
#include "render/renderer.h"
#include "scene/image.h"
#include "vk/context.h"

namespace sm::app {
namespace {

std::vector<uint64_t> stepsToRender(const RenderJob& job, uint64_t available) {
  available = std::max<uint64_t>(available, 1);
  if (job.time == "all") {
    std::vector<uint64_t> all(std::max<uint64_t>(available, 1));
    for (uint64_t i = 0; i < all.size(); ++i) all[i] = i;
    return all;
  }
  char* end = nullptr;
  long long t = std::strtoll(job.time.c_str(), &end, 10);
  if (job.time.empty() || *end || t < 0)
    throw Error("--time: '", job.time, "' is not a step index or 'all'");
  if (uint64_t(t) >= available)
    throw Error("--time: step ", t, " does not exist (the data has ", available, " time step",
                available == 1 ? "" : "s", ": 0 .. ", available - 1, ")");
  return {uint64_t(t)};
}

}  // namespace

void runRender(const RenderJob& job, Collectives& coll) {
  checkImageSize(job);
  Timer total;
  RankShare share = loadRankShare(job.mesh, job.share, coll);
  const double loadSeconds = total.seconds();
  const std::string field = resolveField(job, share.mesh);
  const uint64_t available =
      share.mesh.findField(field) ? share.mesh.findField(field)->numSteps() : 1;
  const std::vector<uint64_t> steps = stepsToRender(job, coll.max(double(available)));
  const std::pair<double, double> range =
      job.range ? *job.range : globalRange(share.mesh, field, steps, coll);

  if (fileExtension(job.out) != ".png" && fileExtension(job.out) != ".pfm")
    throw Error("--out: '", job.out, "' must end in .png or .pfm");
  render::RenderSettings s = makeSettings(job, share, range);
  s.compositeMethod = job.composite;

  Timer prepTimer;
  PreparedShare prepared =
      prepareShare(share, prep::PrepOptions{job.compact}, job.cacheDir, coll.rank(), coll.size());
  const double prepSeconds = prepTimer.seconds();
  vk::Context ctx(contextOptions(job));
  render::GpuScene gpu(ctx, prepared.rank);
  comp::DeepCompositor compositor(ctx, coll.communicator(), job.width, job.height, job.lists);
  render::Renderer renderer(ctx, gpu, compositor);

  StatsReport report(job, coll);
  report.setSetup(loadSeconds, prepSeconds, prepared.fromCache, prepared.rank, gpu,
                  ctx.deviceName(), s);
  for (uint64_t step : steps) {
    // A rank whose clusters carry fewer steps (or none) holds its last one.
    gpu.setScalars(fieldStep(share.mesh, prepared.rank, field,
                             std::min(step, std::max<uint64_t>(available, 1) - 1)));
    render::FrameResult frame = renderer.render(s);
    report.addFrame(step, frame, renderer, compositor);
    const bool sequence = steps.size() > 1;
    writeFrameExtras(job, compositor, frame.pixels, step, sequence, coll);
    if (coll.rank() == 0) {
      scene::Image img(job.width, job.height);
      img.pixels = std::move(frame.pixels);
      scene::writeImage(framePath(job.out, step, sequence), img, job.background);
    }
  }
  report.finish(ctx.validationErrors());
}

}  // namespace sm::app
