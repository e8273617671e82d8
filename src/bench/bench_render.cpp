// shellmarch bench render [--mesh FILE | the demo capsule, generated] [--sizes 512,1024] [--runs N]
//                         [--vtk-runs N] [--integrators linear,partial] [--json FILE] ...
// Frames and samples per second per stage, compacted vs plain, on this machine's Vulkan device;
// VTK's unstructured-grid ray cast mapper on the same mesh, view, size and transfer function in the
// same run; both images' error against the CPU reference (docs/BENCHMARKS.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "bench/bench_render_setup.h"
#include "bench/first_image.h"
#include "bench/reference_images.h"
#include "bench/registry.h"
#include "bench/render_measure.h"
#include "bench/render_report.h"
#include "cli/cli_parsers.h"
#include "comm/single_rank.h"
#include "common/error.h"
#include "common/file_util.h"
#include "common/timer.h"
#include "prep/memory_report.h"
#include "render/step_limits.h"
#include "session/rank_session.h"

namespace sm::app::bench {

render::RenderSettings settingsFor(const RenderArgs& a, const Scenes& sc, int w, int h) {
  render::RenderSettings s;
  s.width = w;
  s.height = h;
  s.camera = scene::frameBounds(sc.share.wholeBounds, scene::parseViewPreset(a.view), double(w) / h,
                                a.fovy);
  s.transferFunction = scene::makeTransferFunction(a.colormap);
  s.transferFunction.lo = sc.range.first;
  s.transferFunction.hi = sc.range.second;
  s.transferFunction.opacityScale = a.opacityScale;
  s.transferFunction.unitDistance = scene::defaultUnitDistance(sc.share.wholeBounds);
  s.dt =
      a.step > 0 ? a.step : scene::defaultStep(sc.share.elementSize.mean(), sc.share.wholeBounds);
  if (a.step > 0) render::checkStepNotBeyondData(a.step, sc.share.wholeBounds);
  // The paper's comparison: a step against VTK's sample distance, and coarser steps for equal
  // error; the element-exact runs (--exact) ask for it.
  s.integration = render::Integration::Sampled;
  s.earlyTermination = a.earlyTermination;
  return s;
}

nlohmann::json cameraJson(const scene::Camera& c) {
  return {{"eye", {c.eye.x, c.eye.y, c.eye.z}},
          {"at", {c.at.x, c.at.y, c.at.z}},
          {"up", {c.up.x, c.up.y, c.up.z}},
          {"fovy_deg", c.fovyDeg}};
}

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  size_t b = 0;
  while (b <= s.size()) {
    size_t e = s.find(',', b);
    if (e == std::string::npos) e = s.size();
    if (e > b) out.push_back(s.substr(b, e - b));
    b = e + 1;
  }
  return out;
}

namespace {

std::string demoMesh(const RenderArgs& a) {
  return a.mesh.empty() ? generatedMesh(a.workDir, demoMeshOptions()) : a.mesh;
}

Scenes loadScenes(const RenderArgs& a, const std::string& path) {
  Scenes sc;
  comm::SingleRank comm;
  ShareOptions so;
  so.read.fields = {a.field};
  Timer t;
  sc.share = loadRankShare(path, so, comm);
  sc.setup["load_seconds"] = t.seconds();
  const mesh::Field* f = sc.share.mesh.findField(a.field);
  if (!f) throw Error("--field: ", path, " has no point field '", a.field, "'");
  sc.values = f->steps.front();
  mesh::Range r = mesh::fieldRange(*f, 0);
  sc.range = r.empty || !(r.lo < r.hi) ? std::pair{0.0, 1.0} : std::pair{r.lo, r.hi};
  sc.refMesh = sc.share.mesh;
  RankShare plainShare = sc.share;
  t.reset();
  sc.compact = prepareShare(sc.share, prep::PrepOptions{true}, "", 0, 1);
  sc.setup["prepare_compacted_seconds"] = t.seconds();
  t.reset();
  sc.plain = prepareShare(plainShare, prep::PrepOptions{false}, "", 0, 1);
  sc.setup["prepare_plain_seconds"] = t.seconds();
  sc.setup["elements"] = sc.compact.rank.numElements();
  sc.setup["vertices"] = sc.compact.rank.numVertices();
  sc.setup["shell_triangles"] = sc.compact.rank.numShellTriangles();
  sc.setup["array"] = f->numSteps() > 1 ? a.field + "@t0" : a.field;
  return sc;
}

// Compacted frames at coarser sample spacings: shellmarch's speed at a given error, so that the
// goals can compare with VTK at equal or lower error (VTK's cost does not depend on a step).
void measureCoarser(const RenderArgs& a, session::RankSession& compact,
                    const render::RenderSettings& s, nlohmann::json& j, RenderImages& images) {
  j["shellmarch"]["compacted_coarser"] = nlohmann::json::array();
  // The stage-split tracer at the default step: traversal and marching timed apart, and what
  // tracing each ray once (the default) saves.
  {
    render::RenderSettings split = s;
    split.segmentCacheBytes = 0;
    RenderMeasurement m = measureRender(compact, split, a.runs);
    nlohmann::json mj = toJson(m);
    mj["dt_scale"] = 1.0;
    mj["dt"] = split.dt;
    mj["stage_split"] = true;
    mj["label"] = "shellmarch compacted stage-split";
    j["shellmarch"]["compacted_coarser"].push_back(mj);
    images.renderers.emplace_back(mj["label"].get<std::string>(), std::move(m.image));
  }
  for (const std::string& item : splitList(a.coarser)) {
    const double k = parsePositive("--coarser", item);
    render::RenderSettings sk = s;
    sk.dt *= k;
    RenderMeasurement m = measureRender(compact, sk, a.runs);
    nlohmann::json mj = toJson(m);
    mj["dt_scale"] = k;
    mj["dt"] = sk.dt;
    mj["label"] = concat("shellmarch compacted dt×", item);
    j["shellmarch"]["compacted_coarser"].push_back(mj);
    images.renderers.emplace_back(mj["label"].get<std::string>(), std::move(m.image));
  }
  // Element-exact integration: tetrahedra are integrated whole whatever dt is; dt only bounds the
  // pieces of the other types' (non-linear) segments.
  for (const std::string& item : splitList(a.exact)) {
    const double k = parsePositive("--exact", item);
    render::RenderSettings sk = s;
    sk.dt *= k;
    sk.integration = render::Integration::ElementExact;
    RenderMeasurement m = measureRender(compact, sk, a.runs);
    nlohmann::json mj = toJson(m);
    mj["dt_scale"] = k;
    mj["dt"] = sk.dt;
    mj["integration"] = "element-exact";
    mj["label"] = concat("shellmarch element-exact", k == 1 ? "" : concat(" dt×", item));
    j["shellmarch"]["compacted_coarser"].push_back(mj);
    images.renderers.emplace_back(mj["label"].get<std::string>(), std::move(m.image));
  }
}

// The CPU references for this view, computed once and kept under the work directory.
void addReferences(const RenderArgs& a, const Scenes& sc, const ref::ReferenceRenderer& ref,
                   const render::RenderSettings& s, nlohmann::json& j, RenderImages& images) {
  const std::string cacheDir = joinPath(a.workDir, "reference");
  for (const std::string& mode : splitList(a.references)) {
    ref::RenderSettings rs;
    rs.dt = s.dt;
    rs.mode = mode == "grid" ? ref::RenderMode::Grid : ref::RenderMode::Converged;
    rs.tolerance = a.refTolerance;
    ReferenceImage r = referenceImage(ref, sc.values, s.camera, s.width, s.height,
                                      s.transferFunction, rs, cacheDir);
    j["references"][mode] = {{"seconds", r.seconds}, {"cached", r.cached}, {"file", r.path}};
    scene::writePngRgba(
        joinPath(a.workDir, concat("reference_", mode, "_", s.width, "x", s.height, ".png")),
        r.image);
    images.references[mode] = std::move(r.image);
  }
}

// The GPU frames of both scenes at one size, then the references (CPU) for that view.
nlohmann::json measureSize(const RenderArgs& a, const Scenes& sc, session::RankSession& compact,
                           session::RankSession& plain, const ref::ReferenceRenderer& ref, int w,
                           int h, RenderImages& images) {
  render::RenderSettings s = settingsFor(a, sc, w, h);
  std::fprintf(stderr, "rendering %dx%d: compacted, plain, coarser steps (%d warm frames each)\n",
               w, h, a.runs);
  RenderMeasurement mc = measureRender(compact, s, a.runs);
  RenderMeasurement mp = measureRender(plain, s, a.runs);
  nlohmann::json j;
  j["width"] = w;
  j["height"] = h;
  j["camera"] = cameraJson(s.camera);
  j["dt"] = s.dt;
  j["shellmarch"]["compacted"] = toJson(mc);
  j["shellmarch"]["plain"] = toJson(mp);
  // Premultiplied RGBA PNGs like VTK's, to look at side by side.
  scene::writePngRgba(joinPath(a.workDir, concat("shellmarch_compacted_", w, "x", h, ".png")),
                      mc.image);
  images.renderers = {{"shellmarch compacted", std::move(mc.image)},
                      {"shellmarch plain", std::move(mp.image)}};
  measureCoarser(a, compact, s, j, images);
  addReferences(a, sc, ref, s, j, images);
  return j;
}

// Lists of names: each at most once (a repeated integrator made VTK render it twice, and every
// paired round then failed on a count that did not match).
std::vector<std::string> namesOnce(const char* option, const std::string& list) {
  std::vector<std::string> names = splitList(list);
  for (size_t i = 0; i < names.size(); ++i)
    if (std::find(names.begin(), names.begin() + long(i), names[i]) != names.begin() + long(i))
      throw Error(option, ": '", names[i], "' is listed twice");
  return names;
}

void runRenderBench(RenderArgs& a) {
  // The checks `render` makes: a bad value would otherwise be measured (a NaN image scored as
  // perfect) or silently replaced by a default.
  if (!a.stepText.empty()) a.step = parsePositive("--step", a.stepText);
  if (!(a.opacityScale >= 0 && std::isfinite(a.opacityScale)))
    throw Error("--opacity-scale: ", a.opacityScale, " must be finite and not negative");
  if (!(a.earlyTermination > 0 && a.earlyTermination <= 1))
    throw Error("--early-termination: ", a.earlyTermination, " is not an opacity in (0, 1]");
  if (!(a.fovy > 0 && a.fovy < 180))
    throw Error("--fovy: ", a.fovy, " must be in (0, 180) degrees");
  if (a.runs < 1 || a.vtkRuns < 1) throw Error("--runs and --vtk-runs: must be at least 1");
  if (a.firstImageRuns < 1) throw Error("--first-image-runs: must be at least 1");
  if (a.firstImage != "none") parseSizes("--first-image", a.firstImage);
  if (a.pairRounds < 0) throw Error("--pair-rounds: must not be negative");
  for (const std::string& r : namesOnce("--references", a.references))
    if (r != "grid" && r != "converged")
      throw Error("--references: '", r, "' (use grid, converged)");
  for (const std::string& i : namesOnce("--integrators", a.integrators))
    if (i != "linear" && i != "partial" && i != "preintegration" && i != "homogeneous")
      throw Error("--integrators: '", i, "' (use linear, partial, preintegration, homogeneous)");
  const std::vector<std::string> measured = splitList(a.integrators);
  for (const std::string& i : namesOnce("--pair-integrators", a.pairIntegrators))
    if (std::find(measured.begin(), measured.end(), i) == measured.end())
      throw Error("--pair-integrators: '", i, "' is not among --integrators (", a.integrators, ")");
  const auto sizes = parseSizes("--sizes", a.sizes);
  std::filesystem::create_directories(a.workDir);
  nlohmann::json report;
  report["benchmark"] = "render";
  report["machine"] = machineJson();
  const std::string mesh = demoMesh(a);
  Scenes sc = loadScenes(a, mesh);
  report["mesh"] = mesh;
  if (a.firstImage != "none") {
    report["first_image"] = measureFirstImage(a, sc, mesh);
    if (a.onlyFirstImage) {
      printFirstImage(report["first_image"]);
      if (!a.json.empty()) writeJsonFile(a.json, report);
      return;
    }
  }
  Timer t;
  ref::ReferenceRenderer ref(sc.refMesh);
  sc.setup["reference_bvh_seconds"] = t.seconds();
  vk::ContextOptions vo;
  vo.device = a.device;
  vo.tracer = parseTracer(a.tracer);
  vk::Context ctx(vo);
  t.reset();
  // One session per element layout, on one device.
  session::RankSession compact(ctx, nullptr), plain(ctx, nullptr);
  compact.setScene(sc.compact.rank, std::move(sc.compact.rank.positions))
      .setScalars(fieldStep(sc.share.mesh, sc.compact.rank, a.field, 0));
  plain.setScene(sc.plain.rank, std::move(sc.plain.rank.positions))
      .setScalars(fieldStep(sc.share.mesh, sc.plain.rank, a.field, 0));
  sc.setup["upload_seconds_both"] = t.seconds();
  sc.setup["device_bytes"] = {{"compacted", compact.scene().deviceBytes()},
                              {"plain", plain.scene().deviceBytes()}};
  auto memC = prep::memoryReport(sc.compact.rank);
  sc.setup["element_bytes"] = {{"compacted", memC.compactedElements},
                               {"plain", memC.plainElements}};
  report["device"] = ctx.deviceName();
  report["tracer"] = vk::tracerName(ctx.tracer());
  report["setup"] = sc.setup;
  report["options"] = {{"field", a.field},
                       {"colormap", a.colormap},
                       {"view", a.view},
                       {"runs", a.runs},
                       {"vtk_runs", a.vtkRuns},
                       {"early_termination", a.earlyTermination},
                       {"reference_tolerance", a.refTolerance},
                       {"opacity_scale", a.opacityScale}};
  report["env"] = {
      {"LP_NUM_THREADS", std::getenv("LP_NUM_THREADS") ? std::getenv("LP_NUM_THREADS") : ""}};
  std::vector<RenderImages> images(sizes.size());
  for (size_t i = 0; i < sizes.size(); ++i)
    report["sizes"].push_back(
        measureSize(a, sc, compact, plain, ref, sizes[i].first, sizes[i].second, images[i]));
  report["vtk"] = runVtk(a, sc, mesh, report["sizes"]);
  addErrorsAndGoals(report, images);
  pairWithVtk(a, sc, mesh, compact, report);
  report["load_average_after"] = machineJson()["load_average"];
  printRenderTables(report);
  if (report.contains("first_image")) printFirstImage(report["first_image"]);
  if (!a.json.empty()) writeJsonFile(a.json, report);
  checkValidation(ctx);
}

}  // namespace

void configureRenderBench(CLI::App& cmd) {
  auto a = std::make_shared<RenderArgs>();
  cmd.add_option("--mesh", a->mesh, "Mesh to render (default: the demo capsule, generated once)");
  cmd.add_option("--field", a->field, "Point field (step 0)")
      ->capture_default_str()
      ->check(nonEmptyName());
  cmd.add_option("--colormap", a->colormap, "Colour map")->capture_default_str();
  cmd.add_option("--view", a->view, "Framing view: iso, +x, -x, ...")->capture_default_str();
  cmd.add_option("--fovy", a->fovy, "Vertical field of view, degrees")->capture_default_str();
  cmd.add_option("--opacity-scale", a->opacityScale, "Multiplies the opacity map")
      ->capture_default_str();
  cmd.add_option("--step", a->stepText,
                 "Sample distance (default: half the mean element size, at most diagonal / 256)");
  cmd.add_option("--early-termination", a->earlyTermination, "shellmarch's early ray termination")
      ->capture_default_str();
  cmd.add_option("--sizes", a->sizes, "Image sizes: N (square) or WxH, comma separated")
      ->capture_default_str();
  allowEmptyValue(
      cmd.add_option(
             "--coarser", a->coarser,
             "Also render compacted at the step times these (speed at equal error; '' for none)")
          ->capture_default_str());
  allowEmptyValue(
      cmd.add_option("--exact", a->exact,
                     "Element-exact runs at the step times these, comma separated (empty: none)")
          ->capture_default_str());
  cmd.add_option("--runs", a->runs, "Warm shellmarch frames per case (after one cold frame)")
      ->capture_default_str();
  cmd.add_option("--vtk-runs", a->vtkRuns, "Warm VTK frames per case")->capture_default_str();
  cmd.add_option("--pair-rounds", a->pairRounds,
                 "Rounds of shellmarch's equal-error run and VTK taking turns (0: none)")
      ->capture_default_str();
  cmd.add_option("--pair-integrators", a->pairIntegrators,
                 "VTK integrators measured in the paired rounds (among --integrators)")
      ->capture_default_str();
  cmd.add_option("--integrators", a->integrators,
                 "VTK ray integrators: linear, partial, preintegration, homogeneous")
      ->capture_default_str();
  cmd.add_option("--references", a->references, "CPU references: grid and/or converged")
      ->capture_default_str();
  cmd.add_option("--ref-tolerance", a->refTolerance, "Converged reference: error per channel")
      ->capture_default_str();
  cmd.add_option("--work-dir", a->workDir, "Generated mesh, reference images, VTK outputs")
      ->capture_default_str();
  cmd.add_option("--device", a->device, "Vulkan device index or name substring");
  cmd.add_option("--tracer", a->tracer, "auto, query or pipeline (bench tracers compares them)")
      ->capture_default_str();
  cmd.add_option("--json", a->json, "Write the results as JSON to this file")
      ->check(writableFile());
  cmd.add_option("--python", a->python, "Python with VTK (python3-vtk9)")->capture_default_str();
  cmd.add_flag("--no-vtk", a->noVtk, "Skip the VTK peer");
  cmd.add_option("--first-image", a->firstImage,
                 "Size of the first-image block: start to PNG in fresh processes, cold and warm "
                 "shader caches, beside VTK ('none': skipped)")
      ->capture_default_str();
  cmd.add_option("--first-image-runs", a->firstImageRuns,
                 "Cold and warm processes (and VTK's) per first-image measurement")
      ->capture_default_str();
  cmd.add_flag("--only-first-image", a->onlyFirstImage, "Measure the first-image block alone");
  cmd.callback([a] { runRenderBench(*a); });
}

}  // namespace sm::app::bench
