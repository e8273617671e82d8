// shellmarch render MESH --field NAME [--time T|all] [--size WxH] [camera] [transfer function]
//                        [--step DT] [--clusters N] [--out FILE.png] [--stats]
#include <map>
#include <memory>

#include "app/cli_parsers.h"
#include "app/commands.h"
#include "app/render_job.h"
#include "app/run_parallel.h"

namespace sm::app {

void registerRender(CLI::App& app) {
  auto* cmd = app.add_subcommand("render", "Render a mesh to a PNG (data-parallel under mpirun)");
  auto job = std::make_shared<RenderJob>();
  auto raw = std::make_shared<std::map<std::string, std::string>>();
  cmd->add_option("mesh", job->mesh, "Mesh file (.vtu, .pvtu, .vtk, .ugrid)")->required();
  cmd->add_option("--field", job->field, "Point field to render (default: the first)");
  cmd->add_option("--time", job->time, "Time step index, or 'all' for a numbered PNG sequence");
  cmd->add_option("--size", (*raw)["--size"], "Image size WxH (default 512x512)");
  cmd->add_option("--eye", (*raw)["--eye"], "Camera position x,y,z");
  cmd->add_option("--at", (*raw)["--at"], "Point looked at x,y,z (default: the data's centre)");
  cmd->add_option("--up", (*raw)["--up"], "Up direction x,y,z (default 0,0,1)");
  cmd->add_option("--fovy", job->fovy, "Vertical field of view in degrees (default 30)");
  cmd->add_option("--view", job->view, "Framing view when no --eye: iso, +x, -x, +y, -y, +z, -z");
  cmd->add_option(
      "--colormap", job->colormap,
      "viridis, cool-to-warm, inferno, plasma, grayscale, jet, turbo, or a ParaView .json");
  cmd->add_option("--range", (*raw)["--range"], "Scalar range LO,HI (default: the field's range)");
  cmd->add_option("--opacity-scale", job->opacityScale, "Multiplies the opacity map (default 1)");
  cmd->add_option("--unit-distance", (*raw)["--unit-distance"],
                  "Length over which opacity 1 gives optical depth 1 (default: diagonal / 8)");
  cmd->add_option("--step", (*raw)["--step"],
                  "Sample distance along rays (default: half the mean element size)");
  cmd->add_option(
      "--integration", (*raw)["--integration"],
      "sampled (fixed step on a global grid, default) or exact (pre-integrated per element)");
  cmd->add_option("--early-termination", job->earlyTermination,
                  "Stop rays at this opacity (default 0.99)");
  cmd->add_option("--background", (*raw)["--background"], "Background colour r,g,b in [0,1]");
  cmd->add_option("--clusters", job->share.metisClusters, "Split into N clusters with METIS");
  cmd->add_option("--cluster-array", job->share.read.clusterArray,
                  "Cell array holding cluster ids");
  cmd->add_option("--lists", (*raw)["--lists"],
                  "Fragment lists: two-pass (exact), drop or merge (fixed K)");
  cmd->add_option("--k", job->lists.fixedK, "Slots per pixel for fixed-length lists (default 8)");
  cmd->add_option("--encoding", (*raw)["--encoding"], "Fragment encoding: float or rgba8");
  auto plain = std::make_shared<bool>(false);
  cmd->add_flag("--plain", *plain, "Keep elements uncompacted (no XOR compaction)");
  cmd->add_option("--device", job->device, "Vulkan device index or name substring");
  cmd->add_option("--cache-dir", job->cacheDir,
                  "Folder for the preparation cache (off by default)");
  cmd->add_option("--out", job->out, "Output image, .png or .pfm (float) (default shellmarch.png)");
  cmd->add_option("--composite", (*raw)["--composite"],
                  "deep (exact, default) or single (one fragment per rank and pixel, as IceT-style "
                  "compositors)");
  cmd->add_option(
      "--l2-heatmap", job->l2Heatmap,
      "Also composite with the other method and write the per-pixel L2 difference heatmap (PNG)");
  cmd->add_option("--heatmaps", job->heatmaps,
                  "Write fragment-count heatmaps PREFIX_rank<r>.png and PREFIX_all.png");
  cmd->add_flag("--stats", job->stats,
                "Print segments and fragments per pixel, lost rays, ms per stage");
  cmd->add_option("--stats-json", job->statsJson, "Write the statistics as JSON to this file");
  cmd->callback([job, raw, plain] {
    auto get = [&](const char* k) -> const std::string& { return (*raw)[k]; };
    if (!get("--size").empty())
      std::tie(job->width, job->height) = parseSize("--size", get("--size"));
    if (!get("--eye").empty()) job->eye = parseVec3("--eye", get("--eye"));
    if (!get("--at").empty()) job->at = parseVec3("--at", get("--at"));
    if (!get("--up").empty()) job->up = parseVec3("--up", get("--up"));
    if (!get("--range").empty()) job->range = parseRange("--range", get("--range"));
    if (!get("--unit-distance").empty())
      job->unitDistance = parsePositive("--unit-distance", get("--unit-distance"));
    if (!get("--step").empty()) job->step = parsePositive("--step", get("--step"));
    if (!get("--background").empty())
      job->background = glm::vec3(parseVec3("--background", get("--background")));
    if (!get("--lists").empty()) job->lists.mode = parseListMode(get("--lists"));
    if (!get("--encoding").empty()) job->lists.encoding = parseEncoding(get("--encoding"));
    if (!get("--composite").empty()) job->composite = parseCompositeMethod(get("--composite"));
    if (!get("--integration").empty()) job->integration = parseIntegration(get("--integration"));
    job->compact = !*plain;
    runParallel([&](Collectives& coll) { runRender(*job, coll); });
  });
}

}  // namespace sm::app
