// shellmarch render MESH --field NAME [--time K|A:B[:S]|t=TIME|all] [--size WxH] [camera]
//                        [transfer function] [--step DT] [--clusters N] [--out FILE.png] [--stats]
//                        [--repeat R] [--no-prefetch] [--orbit N] [--legend]
//                        [--compare BASELINE [--tolerance LEVELS] [--max-share FRACTION]]
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/cli_parsers.h"
#include "cli/commands.h"
#include "cli/image_check.h"
#include "cli/run_parallel.h"
#include "cli/scene_options.h"
#include "common/error.h"
#include "pipeline/render_job.h"
#include "pipeline/time_selection.h"

namespace sm::app {
namespace {

// render --compare: refused before any work (exit status 2, as `compare`) when the image cannot be
// checked: a sequence, a baseline that --out would overwrite, or one unreadable or of another size.
void checkBaseline(const RenderJob& job, CheckFiles& check) {
  if (selectsSequence(job.time) || job.orbit > 1)
    throw UsageError("--compare: checks one image, not a sequence (--time ", job.time,
                     job.orbit > 1 ? concat(", --orbit ", job.orbit) : std::string(), ")");
  check.result = job.out;
  std::error_code ec;
  if (std::filesystem::equivalent(job.out, check.baseline, ec))
    throw UsageError("--compare: '", check.baseline, "' is also the file of --out");
  checkOutputNames(check);
  const CheckImage baseline = readCheckImage(check.baseline, "--compare");
  if (baseline.image.width != job.width || baseline.image.height != job.height)
    throw UsageError("--compare: '", check.baseline, "' is ", baseline.image.width, "x",
                     baseline.image.height, " pixels, the image rendered ", job.width, "x",
                     job.height, " (--size)");
}

}  // namespace

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
  auto check = std::make_shared<CheckFiles>();
  check->resultRole = "--out";
  check->baselineRole = "--compare";
  CLI::Option* compare = cmd->add_option(
      "--compare", check->baseline,
      "Then check the image against this baseline (.png or .pfm) as `shellmarch compare` does, "
      "writing OUT.diff.png: exit status 1 beyond the tolerance");
  auto [tolerance, maxShare] = addToleranceOptions(cmd, check->tolerance);
  tolerance->needs(compare);
  maxShare->needs(compare);
  cmd->add_flag_callback(
      "--no-prefetch", [job] { job->prefetch = false; },
      "Load each step when its frame starts instead of while the frame before renders");
  groupSceneOptions(cmd);
  cmd->footer(
      "Examples:\n"
      "  shellmarch render capsule.pvtu --field density --view +y --size 1920x1080 --legend\n"
      "  shellmarch render run.pvd --field T --time all --colormap \"Cool to Warm\" --out T.png\n"
      "  mpirun -np 8 shellmarch render big.pvtu --field p --range 0,2 --opacity 0.5:0,2:0.6");
  cmd->callback([cmd, job, raw, check] {
    applySceneOptions(*raw, *job);
    // 0 is "no orbit" inside; given on the command line it is a mistake like a negative count.
    if (cmd->count("--orbit") && job->orbit < 1)
      throw Error("--orbit: must be at least 1, not ", job->orbit);
    if (!raw->text["--composite"].empty())
      job->composite = parseCompositeMethod(raw->text["--composite"]);
    if (!check->baseline.empty()) checkBaseline(*job, *check);
    std::optional<ImageCheck> checked;  // on rank 0
    runParallel([&](comm::Communicator& comm) {
      runRender(*job, comm);
      if (!check->baseline.empty() && comm.rank() == 0) checked = runImageCheck(*check, std::cout);
    });
    if (checked && !checked->passed) throw Error(checkFailure(*checked, *check));
  });
}

}  // namespace sm::app
