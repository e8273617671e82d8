// shellmarch bench features [--size N] [--runs N] [--rounds N] [--json F] [--markdown F]
// Pay only for what the scene uses (docs/DESIGN.md): for each feature, the time of a frame when the
// scene does not use it (pipelines specialised without it; measured twice, A/A, so the noise
// floor is on the table), when its code is compiled in but does nothing (what a renderer without
// specialisation would pay), and when it is used (its real cost). Variants of one table are timed
// interleaved, round after round, so that drift in the machine's load hits them alike.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "bench/bench_common.h"
#include "bench/rank_group.h"
#include "bench/registry.h"
#include "cli/cli_checks.h"
#include "common/error.h"
#include "common/file_util.h"
#include "common/timer.h"
#include "compositor/deep_compositor.h"
#include "io/mesh_io.h"
#include "pipeline/rank_pipeline.h"
#include "prep/memory_report.h"
#include "render/gpu_scene.h"
#include "render/renderer.h"
#include "vk/context.h"

namespace sm::app::bench {
namespace {

struct FeatureArgs {
  std::string size = "384";
  int runs = 3, rounds = 3;
  std::string workDir = "out/bench", json, markdown, device;
};

// A prepared mesh on the device and the frame settings that view it.
struct Scene {
  std::string name;
  mesh::UnstructuredMesh mesh;  // kept for the rank groups
  std::vector<float> values;
  PreparedShare compact, plain;
  std::unique_ptr<render::GpuScene> gpuCompact, gpuPlain;
  render::RenderSettings base;
};

std::unique_ptr<Scene> makeScene(const std::string& name, mesh::UnstructuredMesh m,
                                 const std::string& field, const vk::Context& ctx, int w, int h) {
  auto sc = std::make_unique<Scene>();
  sc->name = name;
  const mesh::Field* f = m.findField(field);
  if (!f) throw Error(name, ": no point field '", field, "'");
  sc->values = f->steps[0];
  sc->base = isoFrame(m, *f, "cool-to-warm", w, h);
  sc->mesh = m;
  for (bool compact : {true, false}) {
    RankShare share;
    share.mesh = m;
    share.wholeBounds = m.bounds();
    PreparedShare p = prepareShare(share, prep::PrepOptions{compact}, "", 0, 1);
    auto gpu = std::make_unique<render::GpuScene>(ctx, p.rank, std::move(p.rank.positions));
    gpu->setScalars(prep::gatherScalars(p.rank, sc->values));
    (compact ? sc->gpuCompact : sc->gpuPlain) = std::move(gpu);
    (compact ? sc->compact : sc->plain) = std::move(p);
  }
  return sc;
}

// One way of rendering a scene: which scene buffers, settings and fragment lists.
struct Variant {
  std::string feature, state;  // e.g. "shading", "used"
  const render::GpuScene* scene = nullptr;
  render::RenderSettings settings;
  comp::CompositorOptions lists;
  std::vector<double> ms;
};

// Times the variants interleaved: every variant's renderer is built and warmed (its pipelines
// compiled) first, then each round renders `runs` frames of each in turn.
void timeInterleaved(const vk::Context& ctx, std::vector<Variant>& vs, int runs, int rounds) {
  struct Rig {
    std::unique_ptr<comp::DeepCompositor> compositor;
    std::unique_ptr<render::Renderer> renderer;
  };
  std::vector<Rig> rigs;
  for (Variant& v : vs) {
    Rig r;
    r.compositor = std::make_unique<comp::DeepCompositor>(ctx, nullptr, v.settings.width,
                                                          v.settings.height, v.lists);
    r.renderer = std::make_unique<render::Renderer>(ctx, *v.scene, *r.compositor);
    r.renderer->render(v.settings);  // cold: compiles
    rigs.push_back(std::move(r));
  }
  for (int round = 0; round < rounds; ++round)
    for (size_t i = 0; i < vs.size(); ++i)
      for (int k = 0; k < runs; ++k) {
        Timer t;
        rigs[i].renderer->render(vs[i].settings);
        vs[i].ms.push_back(t.ms());
      }
}

void report(const std::string& title, std::vector<Variant>& vs, Table& table, nlohmann::json& out) {
  const double base = median(vs[0].ms);
  for (const Variant& v : vs) {
    const double m = median(v.ms);
    const double pct = 100.0 * (m - base) / base;
    table.add(
        {title, v.feature, v.state, fixed(m, 1), (pct >= 0 ? "+" : "") + fixed(pct, 1) + "%"});
    out.push_back({{"scene", title},
                   {"feature", v.feature},
                   {"state", v.state},
                   {"ms", m},
                   {"vs_baseline_percent", pct},
                   {"frames", v.ms}});
  }
}

Variant variant(const Scene& sc, const std::string& feature, const std::string& state) {
  Variant v;
  v.feature = feature;
  v.state = state;
  v.scene = sc.gpuCompact.get();
  v.settings = sc.base;
  return v;
}

// A mesh of one element type: specialised for it, A/A, and with every type's code compiled in.
void typeTable(const FeatureArgs& a, const vk::Context& ctx, const Scene& sc, Table& t,
               nlohmann::json& j) {
  std::vector<Variant> vs = {
      variant(sc, "element types", "unused types specialised out (baseline)"),
      variant(sc, "element types", "the same again (A/A: noise floor)"),
      variant(sc, "element types", "all four types compiled in")};
  vs[2].settings.allTypePipelines = true;
  timeInterleaved(ctx, vs, a.runs, a.rounds);
  report(sc.name, vs, t, j);
}

// The mixed demo mesh: shading, sampling (the baseline integrates element-exact, the default),
// compaction, fragment encoding, log scale.
void demoTable(const FeatureArgs& a, const vk::Context& ctx, const Scene& sc, Table& t,
               nlohmann::json& j) {
  std::vector<Variant> vs = {variant(sc, "all", "nothing optional used (baseline)"),
                             variant(sc, "all", "the same again (A/A: noise floor)"),
                             variant(sc, "shading", "compiled in, no effect (ambient 1)"),
                             variant(sc, "shading", "used"),
                             variant(sc, "fixed-step sampling", "used (the paper's integration)"),
                             variant(sc, "XOR compaction", "not used (plain elements)"),
                             variant(sc, "8-bit fragments", "used"),
                             variant(sc, "log scale", "used")};
  vs[2].settings.shading = render::Shading{true, 1.0, 0.0, 0.0, 1.0};
  vs[3].settings.shading.enabled = true;
  vs[4].settings.integration = render::Integration::Sampled;
  vs[5].scene = sc.gpuPlain.get();
  vs[6].lists.encoding = comp::Encoding::Rgba8;
  scene::TransferFunction& log = vs[7].settings.transferFunction;
  log.scale = scene::ScalarScale::Log;
  if (!(log.lo > 0)) log.lo = log.hi * 1e-3;  // a log scale needs a positive range
  timeInterleaved(ctx, vs, a.runs, a.rounds);
  report(sc.name, vs, t, j);
}

// One rank composites locally; several exchange. The exchange's own cost: two in-process ranks
// with every cluster on rank 0, against one.
void rankTable(const FeatureArgs& a, const Scene& sc, Table& t, nlohmann::json& j) {
  std::vector<Variant> vs(2);
  vs[0].feature = vs[1].feature = "exchange between ranks";
  vs[0].state = "one rank: no exchange (baseline)";
  vs[1].state = "two ranks, all work on rank 0: exchange path";
  RankGroup one(sc.mesh, "vortex", 1, 8, a.device),
      two(sc.mesh, "vortex", 2, 8, a.device, Dealing::AllOnRankZero);
  for (int round = 0; round < a.rounds; ++round) {
    vs[0].ms.push_back(one.render(sc.base, {}, a.runs).ms);
    vs[1].ms.push_back(two.render(sc.base, {}, a.runs).ms);
  }
  report(sc.name + " (in-process ranks)", vs, t, j);
}

mesh::UnstructuredMesh analytic(gen::CubeSplit split, int n) {
  mesh::UnstructuredMesh m = gen::cube(split, n);
  gen::addAnalyticFields(m, 1);
  return m;
}

void runFeatureBench(const FeatureArgs& a) {
  if (a.runs < 1 || a.rounds < 1) throw Error("--runs and --rounds: must be at least 1");
  const auto sizes = parseSizes("--size", a.size);
  if (sizes.size() != 1) throw Error("--size: give one size");
  const auto [w, h] = sizes[0];
  std::filesystem::create_directories(a.workDir);
  vk::ContextOptions o;
  o.device = a.device;
  vk::Context ctx(o);
  nlohmann::json rows = nlohmann::json::array();
  Table t({"scene", "feature", "state", "ms/frame", "vs baseline"}, 3);
  std::fprintf(stderr, "features: tetrahedra, hexahedra, demo capsule (%dx%d)\n", w, h);
  typeTable(
      a, ctx,
      *makeScene("cube, 131k tetrahedra", analytic(gen::CubeSplit::Tets6, 28), "vortex", ctx, w, h),
      t, rows);
  typeTable(
      a, ctx,
      *makeScene("cube, 110k hexahedra", analytic(gen::CubeSplit::Hex, 48), "vortex", ctx, w, h), t,
      rows);
  auto capsule =
      makeScene("capsule (demo), 303k mixed",
                io::readMesh(generatedMesh(a.workDir, demoMeshOptions())), "vortex", ctx, w, h);
  demoTable(a, ctx, *capsule, t, rows);
  rankTable(a, *capsule, t, rows);
  const prep::MemoryReport mem = prep::memoryReport(capsule->compact.rank);
  const std::string text =
      concat("Machine: ", machineLine(machineJson()), "\n", w, "x", h, ", median of ",
             a.runs * a.rounds, " frames per variant (", a.rounds, " interleaved rounds of ",
             a.runs, ")\n\n", t.str(), "\nElement records of the capsule: compacted ",
             mem.compactedElements, " bytes, plain ", mem.plainElements, " bytes.\n");
  std::printf("%s", text.c_str());
  if (!a.json.empty())
    writeJsonFile(a.json, {{"benchmark", "features"},
                           {"machine", machineJson()},
                           {"device", ctx.deviceName()},
                           {"size", {w, h}},
                           {"rows", rows},
                           {"element_bytes",
                            {{"compacted", mem.compactedElements}, {"plain", mem.plainElements}}}});
  if (!a.markdown.empty()) writeTextFile(a.markdown, text);
  checkValidation(ctx);
}

}  // namespace

void configureFeatureBench(CLI::App& cmd) {
  auto a = std::make_shared<FeatureArgs>();
  cmd.add_option("--size", a->size, "Image size: N (square) or WxH")->capture_default_str();
  cmd.add_option("--runs", a->runs, "Frames per variant and round")->capture_default_str();
  cmd.add_option("--rounds", a->rounds, "Interleaved rounds over the variants")
      ->capture_default_str();
  cmd.add_option("--work-dir", a->workDir, "Where the demo mesh is generated once")
      ->capture_default_str();
  cmd.add_option("--device", a->device, "Vulkan device index or name substring");
  cmd.add_option("--json", a->json, "Write the results as JSON to this file")
      ->check(writableFile());
  cmd.add_option("--markdown", a->markdown, "Write the table as Markdown to this file");
  cmd.callback([a] { runFeatureBench(*a); });
}

}  // namespace sm::app::bench
