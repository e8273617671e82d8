// shellmarch bench accuracy [--meshes demo,lander,FILE[:FIELD]] [--size WxH] [--runs N]
//                           [--rounds N] [--ranks R] [--clusters C] [--json F] [--markdown F]
//                           [--plot F.png]
// What accuracy costs in time (docs/DESIGN.md, "Accuracy has a price"): every rung of the ladder
// against the double-precision CPU reference's continuous integral (Converged mode), with its time
// per frame. Rungs on one rank: fixed-step sampling at 4, 2, 1, 1/2, 1/4 of the mean element size
// h, element-exact integration (the default), early termination. Rungs on R in-process ranks
// holding interleaved METIS clusters, with the default integration: two-pass lists (exact), 8-bit
// fragments, fixed K = 2, 4, 8 with drop and with merge, and single-fragment (IceT-style)
// compositing.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "bench/bench_common.h"
#include "bench/pareto_plot.h"
#include "bench/rank_group.h"
#include "bench/reference_images.h"
#include "bench/registry.h"
#include "bench/render_measure.h"
#include "cli/cli_checks.h"
#include "comm/single_rank.h"
#include "common/error.h"
#include "common/file_util.h"
#include "io/mesh_io.h"
#include "pipeline/rank_pipeline.h"
#include "pipeline/rank_share.h"
#include "prep/vertex_order.h"
#include "scene/view_defaults.h"
#include "session/rank_session.h"
#include "vk/context.h"

#ifndef SHELLMARCH_SHARED_DATA_DIR
#define SHELLMARCH_SHARED_DATA_DIR "../shared/data"
#endif

namespace sm::app::bench {
namespace {

struct AccuracyArgs {
  // Tetrahedra and mixed (demo, lander, post.vtk), hexahedra written by other tools (can.vtu,
  // notch_stress_fixed.vtk).
  std::string meshes = "demo,lander,post.vtk,can.vtu,notch_stress_fixed.vtk";
  std::string size = "320x240";
  int runs = 3, rounds = 3, ranks = 4, clusters = 32;
  double refTolerance = 1e-4;
  std::string workDir = "out/bench", json, markdown, plot, device;
};

// One data set with its view and transfer function.
struct Case {
  std::string name, path, field, colormap = "viridis";
  std::optional<std::pair<double, double>> range;
  double opacityScale = 1;
  std::optional<scene::Camera> camera;
};

scene::Camera bodyCamera() {  // the demo's view of a unit body at the origin (ci/demo.sh)
  scene::Camera c;
  c.eye = {-6, -9, 4.5};
  c.at = {2.5, 0, 0};
  c.up = {0, 0, 1};
  c.fovyDeg = 32;
  return c;
}

Case makeCase(const AccuracyArgs& a, const std::string& spec) {
  Case c;
  if (spec == "demo" || spec == "lander") {
    gen::CfdMeshOptions o;
    o.body = spec == "demo" ? gen::Body::Capsule : gen::Body::Lander;
    o.targetElements = spec == "demo" ? 300000 : 100000;
    o.clusters = 8;
    o.hexBlock = spec == "demo";
    o.steps = spec == "demo" ? 4 : 1;
    c.name = spec == "demo" ? "capsule (demo)" : "lander";
    c.path = generatedMesh(a.workDir, o);
    c.field = "density";
    c.colormap = "inferno";
    c.range = std::pair{1.5, 6.0};
    c.opacityScale = 2;
    c.camera = bodyCamera();
    return c;
  }
  const size_t colon = spec.rfind(':');
  c.path = colon == std::string::npos ? spec : spec.substr(0, colon);
  if (colon != std::string::npos) c.field = spec.substr(colon + 1);
  if (!fileExists(c.path) && fileExists(joinPath(SHELLMARCH_SHARED_DATA_DIR, c.path)))
    c.path = joinPath(SHELLMARCH_SHARED_DATA_DIR, c.path);
  c.name = std::filesystem::path(c.path).filename().string();
  return c;
}

struct Loaded {
  mesh::UnstructuredMesh mesh;  // whole, input order (reference, rank groups)
  std::vector<float> values;
  render::RenderSettings base;  // default integration, dt h/2, early termination off, two-pass
  double h = 0;                 // mean element size
};

Loaded load(const Case& c, int w, int h) {
  Loaded l;
  l.mesh = io::readMesh(c.path);
  const mesh::Field* f = c.field.empty() ? (l.mesh.fields.empty() ? nullptr : &l.mesh.fields[0])
                                         : l.mesh.findField(c.field);
  if (!f) throw Error(c.path, ": no point field '", c.field, "'");
  l.values = f->steps[0];
  mesh::Range r = mesh::fieldRange(*f, 0);
  render::RenderSettings& s = l.base;
  s.width = w;
  s.height = h;
  s.camera = c.camera ? *c.camera
                      : scene::frameBounds(l.mesh.bounds(), scene::ViewPreset::Iso, double(w) / h);
  s.transferFunction = scene::makeTransferFunction(c.colormap);
  s.transferFunction.lo = c.range ? c.range->first : r.lo;
  s.transferFunction.hi = c.range ? c.range->second : (r.hi > r.lo ? r.hi : r.lo + 1);
  s.transferFunction.opacityScale = c.opacityScale;
  s.transferFunction.unitDistance = scene::defaultUnitDistance(l.mesh.bounds());
  l.h = scene::elementSizeSum(l.mesh).mean();
  s.dt = scene::elementStep(l.h);
  s.earlyTermination = 2.0;  // off: rungs differ by what they say only
  return l;
}

struct Rung {
  std::string tag, label;
  double ms = 0;
  scene::Image image;
  double perPixel = 0;  // samples (or pieces) per covered pixel, or fragments per pixel
  uint64_t overflow = 0, lost = 0;
  bool multiRank = false;
  double vsStep = 0;  // one rank: the median over rounds of its time over step h/2's
};

double coveredPixels(const scene::Image& img) {
  double n = 0;
  for (const auto& p : img.pixels) n += p.a > 0 ? 1 : 0;
  return std::max(n, 1.0);
}

// The one-rank rungs: the sample-step ladder, element-exact, early termination. Timed in turn,
// round after round, so that drift in a shared machine's load hits them alike: a rung's time is
// its median frame over the rounds, its time against step h/2 the median of the rounds' ratios.
void singleRankRungs(const AccuracyArgs& a, const Loaded& l, std::vector<Rung>& rungs) {
  comm::SingleRank comm;
  RankShare share;
  share.mesh = l.mesh;
  share.wholeBounds = l.mesh.bounds();
  PreparedShare p = prepareShare(share, prep::PrepOptions{true}, "", 0, 1);
  vk::ContextOptions o;
  o.device = a.device;
  session::RankSession session(o, nullptr);
  const vk::Context& ctx = session.context();
  session.setScene(p.rank, std::move(p.rank.positions))
      .setScalars(prep::gatherScalars(p.rank, l.values));
  const struct {
    const char *tag, *label;
    double k;
  } steps[] = {{"4H", "step 4h", 4},
               {"2H", "step 2h", 2},
               {"H", "step h", 1},
               {"H/2", "step h/2 (default step)", 0.5},
               {"H/4", "step h/4", 0.25}};
  std::vector<std::pair<Rung, render::RenderSettings>> ladder;
  for (const auto& st : steps) {
    render::RenderSettings s = l.base;
    s.integration = render::Integration::Sampled;
    s.dt = st.k * l.h;
    ladder.push_back({Rung{st.tag, st.label}, s});
  }
  render::RenderSettings s = l.base;
  s.integration = render::Integration::ElementExact;
  ladder.push_back({Rung{"EX", "element-exact (default)"}, s});
  s = l.base;
  s.integration = render::Integration::Sampled;
  s.earlyTermination = 0.99;
  ladder.push_back({Rung{"ET", "step h/2, early termination 0.99"}, s});
  std::vector<std::vector<double>> frames(ladder.size()), ratios(ladder.size());
  for (int round = 0; round < a.rounds; ++round) {
    std::vector<double> ms(ladder.size());
    for (size_t i = 0; i < ladder.size(); ++i) {
      RenderMeasurement m = measureRender(session, ladder[i].second, a.runs);
      ms[i] = median(m.totalMs);
      frames[i].insert(frames[i].end(), m.totalMs.begin(), m.totalMs.end());
      Rung& r = ladder[i].first;
      r.image = std::move(m.image);
      r.perPixel = double(m.samples) / coveredPixels(r.image);
      r.lost = m.lostRays;
    }
    for (size_t i = 0; i < ladder.size(); ++i) ratios[i].push_back(ms[i] / ms[3]);  // step h/2
  }
  for (size_t i = 0; i < ladder.size(); ++i) {
    Rung& r = ladder[i].first;
    r.ms = median(frames[i]);
    r.vsStep = median(ratios[i]);
    rungs.push_back(std::move(r));
  }
  checkValidation(ctx);
}

// The rungs that need several ranks: list management, fragment encoding, compositing method.
void multiRankRungs(const AccuracyArgs& a, const Loaded& l, const std::string& field,
                    std::vector<Rung>& rungs) {
  RankGroup group(l.mesh, field, a.ranks, a.clusters, a.device);
  const std::string prefix = concat(a.ranks, " ranks: ");
  auto add = [&](const std::string& tag, const std::string& label,
                 const comp::CompositorOptions& lists, comp::CompositeMethod method) {
    render::RenderSettings s = l.base;
    s.compositeMethod = method;
    GroupFrame f = group.render(s, lists, a.runs);
    Rung r{tag,        prefix + label, f.ms, std::move(f.image), f.fragmentsPerPixel,
           f.overflow, f.lostRays,     true};
    rungs.push_back(std::move(r));
  };
  comp::CompositorOptions two;
  add("2P", "two-pass lists", two, comp::CompositeMethod::Deep);
  comp::CompositorOptions rgba8;
  rgba8.encoding = comp::Encoding::Rgba8;
  add("8B", "8-bit fragments", rgba8, comp::CompositeMethod::Deep);
  for (comp::ListMode mode : {comp::ListMode::FixedDrop, comp::ListMode::FixedMerge})
    for (uint32_t k : {2u, 4u, 8u}) {
      comp::CompositorOptions o;
      o.mode = mode;
      o.fixedK = k;
      const bool drop = mode == comp::ListMode::FixedDrop;
      add(concat(drop ? "D" : "M", k), concat("K=", k, drop ? " drop" : " merge"), o,
          comp::CompositeMethod::Deep);
    }
  add("1F", "single-fragment compositing", two, comp::CompositeMethod::SingleFragment);
}

std::string sci(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2e", v);
  return buf;
}

struct MeshResult {
  Case c;
  nlohmann::json json;
  PlotPanel oneRank, ranks;  // times are comparable within a panel only
  std::string table;
};

MeshResult measureCase(const AccuracyArgs& a, const std::string& spec, int w, int h) {
  MeshResult out;
  out.c = makeCase(a, spec);
  std::fprintf(stderr, "accuracy: %s (%s)\n", out.c.name.c_str(), out.c.path.c_str());
  Loaded l = load(out.c, w, h);
  const std::string field = out.c.field.empty() ? l.mesh.fields[0].name : out.c.field;
  // The reference numbers vertices in the GPU's global (position) order: a quad is split through
  // its smallest vertex in that order, so only then are warped quads triangulated alike (can.vtu's
  // crumpled hexahedra: RMSE 7.3e-4 against an input-order reference, 1.2e-4 against this one).
  const std::vector<uint32_t> order =
      prep::globalVertexOrder(l.mesh.points, prep::makeGlobalFrame(l.mesh.bounds()));
  mesh::UnstructuredMesh refMesh = l.mesh;
  std::vector<uint32_t> newId(order.size());
  std::vector<float> refValues(order.size());
  for (size_t i = 0; i < order.size(); ++i) {
    newId[order[i]] = uint32_t(i);
    refMesh.points[i] = l.mesh.points[order[i]];
    refValues[i] = l.values[order[i]];
  }
  for (auto& cells : refMesh.cells)
    for (uint32_t& v : cells) v = newId[v];
  ref::ReferenceRenderer reference(refMesh);
  ref::RenderSettings rs;
  rs.dt = l.base.dt;
  rs.mode = ref::RenderMode::Converged;
  rs.tolerance = a.refTolerance;
  ReferenceImage ri = referenceImage(reference, refValues, l.base.camera, w, h,
                                     l.base.transferFunction, rs, joinPath(a.workDir, "reference"));
  std::vector<Rung> rungs;
  singleRankRungs(a, l, rungs);
  multiRankRungs(a, l, field, rungs);
  const double baseMs = rungs[3].ms;  // step h/2 on one rank: the paper's method at our step
  // The multi-rank rungs also against the exact two-pass image of the same ranks: what list
  // management, encoding and compositing add on top of the sampling error.
  const scene::Image& twoPass = rungs[7].image;
  Table t({"rung", "ms/frame", "time vs step h/2", "RMSE", "max abs", "PSNR dB", "RMSE vs two-pass",
           "per pixel", "overflow"});
  nlohmann::json rj = nlohmann::json::array();
  for (const Rung& r : rungs) {
    const scene::ImageError e = scene::compareImages(ri.image, r.image);
    const std::string vsTwoPass =
        r.multiRank ? sci(scene::compareImages(twoPass, r.image).rmse) : "-";
    const double vsStep = r.multiRank ? r.ms / baseMs : r.vsStep;
    t.add({r.label, fixed(r.ms, 1), fixed(vsStep, 2) + "x", sci(e.rmse), sci(e.maxAbs),
           fixed(e.psnr, 1), vsTwoPass,
           concat(fixed(r.perPixel, 1), r.multiRank ? " frag" : " smp"), concat(r.overflow)});
    rj.push_back({{"rung", r.label},
                  {"ms", r.ms},
                  {"time_vs_step", vsStep},
                  {"rmse", e.rmse},
                  {"max_abs", e.maxAbs},
                  {"psnr", e.psnr},
                  {"nan_pixels", e.nanPixels},
                  {r.multiRank ? "fragments_per_pixel" : "samples_per_pixel", r.perPixel},
                  {"overflow", r.overflow},
                  {"lost_rays", r.lost},
                  {"ranks", r.multiRank ? a.ranks : 1}});
    (r.multiRank ? out.ranks : out.oneRank).points.push_back({r.tag, r.label, r.ms, e.rmse});
  }
  out.oneRank.title = out.c.name + ", 1 rank";
  out.ranks.title = concat(out.c.name, ", ", a.ranks, " ranks");
  for (size_t i : paretoFront(out.oneRank.points)) rj[i]["pareto"] = true;
  for (size_t i : paretoFront(out.ranks.points)) rj[out.oneRank.points.size() + i]["pareto"] = true;
  out.table = t.str();
  out.json = {{"mesh", out.c.name},
              {"rounds", a.rounds},
              {"path", out.c.path},
              {"field", field},
              {"elements", l.mesh.numCells()},
              {"mean_element_size", l.h},
              {"default_step", l.base.dt},
              {"reference",
               {{"mode", "converged"},
                {"tolerance", a.refTolerance},
                {"seconds", ri.seconds},
                {"cached", ri.cached}}},
              {"rungs", rj}};
  std::printf(
      "\n%s: %llu elements, mean element size h = %.4g, %dx%d, %d warm frames per rung (one "
      "rank: in each of %d rounds)\n%s",
      out.c.name.c_str(), (unsigned long long)l.mesh.numCells(), l.h, w, h, a.runs, a.rounds,
      out.table.c_str());
  std::fflush(stdout);
  return out;
}

// The --meshes list, checked before any work: an empty list or entry would measure nothing and
// still write a report that looks complete.
std::vector<std::string> meshNames(const std::string& list) {
  std::vector<std::string> names;
  size_t b = 0;
  while (true) {
    const size_t e = std::min(list.find(',', b), list.size());
    if (e == b) throw Error("--meshes: empty entry in '", list, "'");
    names.push_back(list.substr(b, e - b));
    if (e == list.size()) return names;
    b = e + 1;
  }
}

void runAccuracyBench(const AccuracyArgs& a) {
  if (a.runs < 1) throw Error("--runs: must be at least 1");
  if (a.rounds < 1) throw Error("--rounds: must be at least 1");
  const std::vector<std::string> names = meshNames(a.meshes);
  const auto sizes = parseSizes("--size", a.size);
  if (sizes.size() != 1) throw Error("--size: give one size, not ", sizes.size());
  std::filesystem::create_directories(a.workDir);
  nlohmann::json report;
  report["benchmark"] = "accuracy";
  report["machine"] = machineJson();
  std::vector<PlotPanel> panels;
  std::string markdown = concat("Machine: ", machineLine(report["machine"]), "\n");
  for (const std::string& name : names) {
    MeshResult r = measureCase(a, name, sizes[0].first, sizes[0].second);
    report["meshes"].push_back(r.json);
    panels.push_back(r.oneRank);
    panels.push_back(r.ranks);
    markdown +=
        concat("\n### ", r.c.name, "\n\n", r.json["elements"].get<uint64_t>(),
               " elements, h = ", r.json["mean_element_size"].get<double>(), "\n\n", r.table);
  }
  report["load_average_after"] = machineJson()["load_average"];
  if (!a.json.empty()) writeJsonFile(a.json, report);
  if (!a.markdown.empty()) writeTextFile(a.markdown, markdown);
  if (!a.plot.empty()) writeErrorTimePlot(a.plot, panels, 2, defaultPython());
}

}  // namespace

void configureAccuracyBench(CLI::App& cmd) {
  auto a = std::make_shared<AccuracyArgs>();
  cmd.add_option("--meshes", a->meshes,
                 "demo, lander (generated once under --work-dir) and files (FILE or FILE:FIELD; "
                 "names in ../shared/data are found there)")
      ->capture_default_str();
  cmd.add_option("--size", a->size, "Image size WxH")->capture_default_str();
  cmd.add_option("--runs", a->runs,
                 "Warm frames per rung and round (after one cold frame); the median counts")
      ->capture_default_str();
  cmd.add_option("--rounds", a->rounds,
                 "Rounds of the one-rank rungs, timed in turn (their time against step h/2: "
                 "the median of the rounds' ratios)")
      ->capture_default_str();
  cmd.add_option("--ranks", a->ranks, "In-process ranks for the list and compositing rungs")
      ->capture_default_str();
  cmd.add_option("--clusters", a->clusters, "METIS clusters dealt round-robin to those ranks")
      ->capture_default_str();
  cmd.add_option("--ref-tolerance", a->refTolerance, "Converged reference: error per channel")
      ->capture_default_str();
  cmd.add_option("--work-dir", a->workDir, "Generated meshes and cached reference images")
      ->capture_default_str();
  cmd.add_option("--device", a->device, "Vulkan device index or name substring");
  cmd.add_option("--json", a->json, "Write the results as JSON to this file")
      ->check(writableFile());
  cmd.add_option("--markdown", a->markdown, "Write the tables as Markdown to this file");
  cmd.add_option("--plot", a->plot, "Write the error-against-time plot (PNG, Pareto front marked)");
  cmd.callback([a] { runAccuracyBench(*a); });
}

}  // namespace sm::app::bench
