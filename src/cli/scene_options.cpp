#include "cli/scene_options.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/common.hpp>
#include <glm/vector_relational.hpp>

#include "cli/cli_parsers.h"
#include "common/check.h"
#include "common/error.h"
#include "common/setting_error.h"
#include "scene/camera_file.h"

namespace sm::app {

void addSceneOptions(CLI::App* cmd, RenderJob& job, SceneOptionText& raw,
                     const std::string& timeHelp) {
  auto& t = raw.text;
  cmd->add_option("mesh", job.mesh,
                  "Mesh file (.vtu, .pvtu, .vtm, .vtk, .ugrid; time series as .pvd or .series)")
      ->required();
  cmd->add_option(
         "--field", job.field,
         "Field to render: NAME, a component NAME[k], or cell data (averaged onto the points); "
         "default: the first point field")
      ->check(nonEmptyName());
  cmd->add_option("--eye", t["--eye"], "Camera position x,y,z");
  cmd->add_option("--at", t["--at"], "Point looked at x,y,z (default: the data's centre)");
  cmd->add_option("--up", t["--up"],
                  "Up direction x,y,z (default 0,0,1; 0,1,0 when looking along z, as the +z "
                  "and -z views do)");
  raw.fovy = cmd->add_option("--fovy", job.fovy, "Vertical field of view in degrees (default 30)");
  cmd->add_option("--view", t["--view"], "Framing view when no --eye: iso, +x, -x, +y, -y, +z, -z");
  cmd->add_flag("--parallel", raw.parallel,
                "Parallel projection: rays along the viewing direction from the plane through "
                "the eye");
  cmd->add_option("--parallel-scale", t["--parallel-scale"],
                  "Half the image's height in world units, as ParaView's (implies --parallel; "
                  "default: the data's bounding sphere fits)");
  cmd->add_option("--camera", t["--camera"],
                  "ParaView camera file (.pvcc, File > Save Camera): eye, point looked at, up, "
                  "angle and projection; --eye, --at, --up, --fovy, --parallel and "
                  "--parallel-scale override its values");
  cmd->add_option(
      "--colormap", job.colormap,
      "viridis, cool-to-warm, inferno, plasma, grayscale, jet, turbo, a ParaView preset name "
      "(\"Cool to Warm\", \"Viridis (matplotlib)\", \"X Ray\", ...: docs/TRANSFER_FUNCTIONS.md), "
      "or a ParaView .json (FILE.json:NAME: one map of a preset file)");
  cmd->add_option("--range", t["--range"], "Scalar range LO,HI (default: the field's range)");
  cmd->add_option("--opacity", t["--opacity"],
                  "Opacity map as VALUE:OPACITY points in data values, linear between them "
                  "(e.g. 2:0,3:0.8,6:0.8); default: the colour map's (a ramp over the range)");
  cmd->add_flag("--log-scale", raw.logScale,
                "Map the field's logarithm onto the colour and opacity maps (a positive range; "
                "for fields that span decades)");
  cmd->add_option("--nan-color", t["--nan-color"],
                  "Colour of NaN and infinite values R,G,B[,OPACITY] in [0,1] (opacity 1 if not "
                  "given, as the table's); default: transparent, or a ParaView map's NanColor and "
                  "NanOpacity");
  cmd->add_option("--opacity-scale", job.opacityScale, "Multiplies the opacity map (default 1)");
  cmd->add_option("--unit-distance", t["--unit-distance"],
                  "Length over which opacity 1 gives optical depth 1 (default: diagonal / 8)");
  cmd->add_option("--step", t["--step"],
                  "Sample distance along rays (default: half the mean element size, at most the "
                  "data's diagonal / 256)");
  cmd->add_option(
      "--integration", t["--integration"],
      "exact (pre-integrated per element, default) or sampled (fixed step on a global grid)");
  cmd->add_flag("--all-type-pipelines", job.allTypePipelines,
                "Benchmarks: pipelines for every element type whatever the mesh holds")
      ->group("");  // hidden: measures what specialisation saves
  cmd->add_flag("--shading", raw.shading,
                "Blinn-Phong shading from the scalar gradient, headlight (off by default)");
  cmd->add_option("--shading-params", t["--shading-params"],
                  "Shading coefficients AMBIENT,DIFFUSE,SPECULAR,SHININESS (default "
                  "0.3,0.7,0.2,20; implies --shading)");
  cmd->add_option("--early-termination", job.earlyTermination,
                  "Stop rays at this opacity (default 0.99)");
  // Registered after the camera and transfer function: the help lists groups in the order of
  // their first option (groupSceneOptions).
  cmd->add_option("--time", job.time, timeHelp);
  cmd->add_option("--size", t["--size"], "Image size WxH (default 512x512)");
  cmd->add_option("--background", t["--background"],
                  "Background colour r,g,b in [0,1], or 'transparent' (render: an RGBA PNG with "
                  "the frame's alpha)");
  cmd->add_flag("--legend", job.legend,
                "Draw the colour legend (the colour map with the field's name and range) at the "
                "right of the image");
  cmd->add_option("--clip", raw.clip,
                  "Clip plane PX,PY,PZ,NX,NY,NZ (keeps the side the normal N points to) or "
                  "AXIS>V / AXIS<V (e.g. x>0.5); repeat for up to 6 planes")
      ->allow_extra_args(false);
  cmd->add_option("--clusters", t["--clusters"], "Split into N clusters with METIS");
  cmd->add_option("--cluster-array", job.share.read.clusterArray, "Cell array holding cluster ids")
      ->check(nonEmptyName());
  cmd->add_option("--lists", t["--lists"],
                  "Fragment lists: two-pass (exact), drop or merge (fixed K)");
  cmd->add_option("--k", t["--k"], "Slots per pixel for fixed-length lists (default 8)");
  cmd->add_option("--encoding", t["--encoding"], "Fragment encoding: float or rgba8");
  cmd->add_option("--pixel-ownership", t["--pixel-ownership"],
                  "Which rank composites which pixels: interleaved (default, balanced whatever "
                  "the view) or ranges (contiguous blocks, the paper's layout)");
  cmd->add_flag("--plain", raw.plain, "Keep elements uncompacted (no XOR compaction)");
  cmd->add_option("--device", job.device, "Vulkan device index or name substring")
      ->check(nonEmptyName());
  cmd->add_option("--tracer", t["--tracer"],
                  "How shell crossings are traced: auto (default: ray queries where the device "
                  "offers them, else a ray tracing pipeline), query or pipeline");
  cmd->add_option("--cache-dir", job.cacheDir,
                  "Folder for the caches: compiled shaders (by default $SHELLMARCH_CACHE_DIR, "
                  "$XDG_CACHE_HOME/shellmarch or ~/.cache/shellmarch) and prepared meshes (only "
                  "with this option); 'none' for no cache");
}

namespace {

// The help's groups, in the order they are shown. An option of render or view not named here is
// a programming error (groupSceneOptions checks): add it to the group a user would look in.
const std::vector<std::pair<std::string, std::vector<std::string>>>& optionGroups() {
  // clang-format off
  static const std::vector<std::pair<std::string, std::vector<std::string>>> groups = {
      {"Data", {"mesh", "--field", "--clusters", "--cluster-array"}},
      {"Camera",
       {"--view", "--eye", "--at", "--up", "--fovy", "--parallel", "--parallel-scale", "--camera",
        "--save-camera", "--orbit"}},
      {"Transfer function",
       {"--colormap", "--range", "--opacity", "--log-scale", "--opacity-scale", "--unit-distance",
        "--nan-color", "--integration", "--step", "--shading", "--shading-params",
        "--early-termination"}},
      {"Time", {"--time", "--no-prefetch", "--play", "--fps"}},
      {"Output",
       {"--size", "--out", "--background", "--legend", "--clip", "--stats", "--stats-json",
        "--compare", "--tolerance", "--max-share", "--screenshot", "--print-camera",
        "--frames", "--script", "--headless", "--no-overlay", "--interactive-scale",
        "--help-controls", "--help-script"}},
      {"Parallel and fragment lists",
       {"--lists", "--k", "--encoding", "--pixel-ownership", "--composite", "--plain"}},
      {"Device and caches", {"--device", "--tracer", "--cache-dir"}},
      {"Diagnostics and benchmarks", {"--repeat", "--l2-heatmap", "--heatmaps", "--dump-counts"}},
  };
  // clang-format on
  return groups;
}

}  // namespace

void groupSceneOptions(CLI::App* cmd) {
  for (CLI::Option* o : cmd->get_options()) {
    const std::string name =
        o->get_lnames().empty() ? o->get_single_name() : "--" + o->get_lnames().front();
    if (o->get_group().empty() || name == "--help") continue;  // hidden, or -h
    bool found = false;
    for (const auto& [group, names] : optionGroups())
      if (std::find(names.begin(), names.end(), name) != names.end()) {
        o->group(group);
        found = true;
      }
    SM_CHECK_MSG(found,
                 "option " << name << " of " << cmd->get_name() << " belongs to no help group");
  }
}

namespace {

// --camera, --parallel and --parallel-scale; the options given override the file's values.
void applyCameraOptions(SceneOptionText& raw, RenderJob& job) {
  const std::string& file = raw.text["--camera"];
  const std::string& scale = raw.text["--parallel-scale"];
  if (!file.empty()) {
    if (!raw.text["--view"].empty())
      throw Error(
          "--view and --camera: give one (--view frames the data, --camera places the "
          "camera as the file says)");
    const scene::Camera c = scene::readCameraFile(file);
    if (!job.eye) job.eye = c.eye;
    if (!job.at) job.at = c.at;
    if (!job.up) job.up = c.up;
    if (!(raw.fovy && raw.fovy->count())) job.fovy = c.fovyDeg;
    job.parallel = c.parallel;
    if (c.parallel) job.parallelScale = c.parallelScale;
  }
  if (raw.parallel) job.parallel = true;
  if (!scale.empty()) {
    job.parallelScale = parsePositive("--parallel-scale", scale);
    if (!(*job.parallelScale < 1e30))
      throw SettingError("parallel-scale", scale, " is beyond the renderer's range (1e30)");
    job.parallel = true;
  }
}

}  // namespace

void applySceneOptions(SceneOptionText& raw, RenderJob& job) {
  auto get = [&](const char* k) -> const std::string& { return raw.text[k]; };
  if (!get("--size").empty()) std::tie(job.width, job.height) = parseSize("--size", get("--size"));
  if (!get("--eye").empty()) job.eye = parseVec3("--eye", get("--eye"));
  if (!get("--at").empty()) job.at = parseVec3("--at", get("--at"));
  if (!get("--up").empty()) job.up = parseVec3("--up", get("--up"));
  if (!get("--range").empty()) job.range = parseRange("--range", get("--range"));
  if (!get("--opacity").empty())
    job.opacityPoints = parseOpacityPoints("--opacity", get("--opacity"));
  if (!get("--unit-distance").empty())
    job.unitDistance = parsePositive("--unit-distance", get("--unit-distance"));
  if (!get("--step").empty()) job.step = parsePositive("--step", get("--step"));
  if (!get("--nan-color").empty()) job.nanColor = parseNanColor("--nan-color", get("--nan-color"));
  job.transparent = get("--background") == "transparent";
  if (!get("--background").empty() && !job.transparent)
    job.background = glm::vec3(parseVec3("--background", get("--background")));
  if (!get("--lists").empty()) job.lists.mode = parseListMode(get("--lists"));
  if (!get("--tracer").empty()) job.tracer = parseTracer(get("--tracer"));
  if (!get("--encoding").empty()) job.lists.encoding = parseEncoding(get("--encoding"));
  if (!get("--pixel-ownership").empty())
    job.lists.ownership = parsePixelOwnership(get("--pixel-ownership"));
  if (!get("--integration").empty()) job.integration = parseIntegration(get("--integration"));
  if (!get("--shading-params").empty())
    job.shading = parseShading("--shading-params", get("--shading-params"));
  if (raw.shading) job.shading.enabled = true;
  job.logScale = raw.logScale;
  job.compact = !raw.plain;
  job.clipPlanes.clear();
  for (const std::string& c : raw.clip) job.clipPlanes.push_back(parseClipPlane("--clip", c));
  scene::checkClipPlanes(job.clipPlanes);
  // Options that another one makes meaningless are refused rather than silently ignored.
  if (!get("--view").empty()) {
    if (job.eye)
      throw Error("--view and --eye: give one (--view frames the data, --eye places the camera)");
    if (job.at || job.up)
      throw Error("--view and ", job.at ? "--at" : "--up",
                  ": give one (--view frames the data; --at and --up go with --eye)");
    job.view = get("--view");
  }
  applyCameraOptions(raw, job);
  if (!(job.fovy > 0 && job.fovy < 180))
    throw SettingError("fovy", job.fovy, " degrees is not in (0, 180)");
  // The device computes in float: a camera beyond its range would see nothing, silently.
  for (const auto& [option, v] : {std::pair{"--eye", job.eye}, std::pair{"--at", job.at}})
    if (v && !(glm::all(glm::lessThanEqual(glm::abs(*v), glm::dvec3(1e30)))))
      throw SettingError(optionKey(option),
                         "components beyond 1e30 in size are out of the renderer's range");
  if (!get("--k").empty()) {
    const int64_t k = parseCount("--k", get("--k"), "slot count", 65535, "65535");
    if (job.lists.mode == comp::ListMode::TwoPass)
      throw SettingError("k",
                         "slots are for fixed-length lists (--lists drop or merge); two-pass lists "
                         "hold every fragment");
    job.lists.fixedK = uint32_t(k);
  }
  if (!get("--clusters").empty() && !job.share.read.clusterArray.empty())
    throw Error(
        "--clusters and --cluster-array: give one (--clusters N makes new clusters with "
        "METIS, --cluster-array reads the file's)");
  if (!get("--clusters").empty())
    job.share.metisClusters =
        int(parseCount("--clusters", get("--clusters"), "cluster count", 1 << 30, "2^30"));
  if (!(job.earlyTermination > 0 && job.earlyTermination <= 1))
    throw SettingError("early-termination", job.earlyTermination,
                       " is not an opacity in (0, 1] (1: rays stop only when opaque)");
  if (!(job.opacityScale >= 0 && std::isfinite(job.opacityScale)))
    throw SettingError("opacity-scale", job.opacityScale, " must be finite and not negative");
  for (int c = 0; c < 3; ++c)
    if (!(job.background[c] >= 0 && job.background[c] <= 1))
      throw SettingError("background", "each component must be in [0, 1], not ", job.background[c]);
}

}  // namespace sm::app
