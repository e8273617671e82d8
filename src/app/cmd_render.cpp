// shellmarch render MESH --field NAME [--time K|A:B[:S]|t=TIME|all] [--size WxH] [camera]
//                        [transfer function] [--step DT] [--clusters N] [--out FILE.png] [--stats]
//                        [--repeat R] [--no-prefetch] [--orbit N] [--legend]
#include <memory>

#include "app/cli_parsers.h"
#include "app/commands.h"
#include "app/render_job.h"
#include "app/run_parallel.h"
#include "app/scene_options.h"
#include "common/error.h"

namespace sm::app {

void registerRender(CLI::App& app) {
  auto* cmd = app.add_subcommand("render", "Render a mesh to a PNG (data-parallel under mpirun)");
  auto job = std::make_shared<RenderJob>();
  auto raw = std::make_shared<SceneOptionText>();
  addSceneOptions(cmd, *job, *raw,
                  "Time step K, a range FIRST:LAST[:STRIDE] or 'all' (a numbered image "
                  "sequence), or t=TIME: the step nearest that time value");
  cmd->add_option("--out", job->out, "Output image, .png or .pfm (float) (default shellmarch.png)");
  cmd->add_option("--composite", raw->text["--composite"],
                  "deep (exact, default) or single (one fragment per rank and pixel, as IceT-style "
                  "compositors)");
  cmd->add_option(
      "--l2-heatmap", job->l2Heatmap,
      "Also composite with the other method and write the per-pixel L2 difference heatmap (PNG)");
  cmd->add_option("--heatmaps", job->heatmaps,
                  "Write fragment-count heatmaps PREFIX_rank<r>.png and PREFIX_all.png");
  cmd->add_option("--dump-counts", job->dumpCounts,
                  "Write every rank's per-pixel fragment counts to this file, for "
                  "`shellmarch_bench_compositor replay --dump FILE`");
  cmd->add_flag("--stats", job->stats,
                "Print segments and fragments per pixel, lost rays, ms per stage");
  cmd->add_option("--stats-json", job->statsJson, "Write the statistics as JSON to this file");
  cmd->add_option(
      "--repeat", job->repeat,
      "Render the step sequence R times and report fps over the runs (images are written "
      "once)");
  cmd->add_option("--orbit", job->orbit,
                  "Turn the camera 360/N degrees about its up axis through the point looked at "
                  "each frame: with one time step, N frames (one turn) as a numbered image "
                  "sequence; with several, one frame per step");
  cmd->add_flag_callback(
      "--no-prefetch", [job] { job->prefetch = false; },
      "Load each step when its frame starts instead of while the frame before renders");
  cmd->callback([cmd, job, raw] {
    applySceneOptions(*raw, *job);
    // 0 is "no orbit" inside; given on the command line it is a mistake like a negative count.
    if (cmd->count("--orbit") && job->orbit < 1)
      throw Error("--orbit: must be at least 1, not ", job->orbit);
    if (!raw->text["--composite"].empty())
      job->composite = parseCompositeMethod(raw->text["--composite"]);
    runParallel([&](Collectives& coll) { runRender(*job, coll); });
  });
}

}  // namespace sm::app
