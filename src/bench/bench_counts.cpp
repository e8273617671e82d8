// shellmarch bench counts [--mesh FILE | the demo capsule] [--ranks 72,552]
//                         [--sizes 512,1024] [--dump-dir DIR] [--json F] [--markdown F]
// The exchange at rank counts this machine cannot run (the paper's 72 and 552), from real frames:
// the mesh is split into METIS clusters dealt round-robin to N virtual ranks; each virtual rank's
// share is prepared and rendered on the device in turn, exactly as that rank would render it, and
// its per-pixel fragment counts are dumped (compositor/count_dump.h). The dump is then replayed
// through the exchange logic (compositor/replay.h) for bytes per rank and load imbalance.
// `shellmarch_bench_compositor replay --dump FILE` replays a dump again without rendering.
#include <cstdio>
#include <filesystem>

#include "bench/bench_common.h"
#include "bench/registry.h"
#include "cli/cli_parsers.h"
#include "common/error.h"
#include "common/file_util.h"
#include "common/timer.h"
#include "compositor/tools/count_dump.h"
#include "compositor/tools/replay.h"
#include "io/mesh_io.h"
#include "partition/partition.h"
#include "prep/prepare.h"
#include "render/gpu_scene.h"
#include "render/renderer.h"
#include "vk/context.h"

namespace sm::app::bench {
namespace {

struct CountArgs {
  std::string mesh;  // "" = the demo capsule (ci/demo.sh's options), generated under workDir
  std::string field = "vortex", colormap = "cool-to-warm";
  std::string ranks = "72,552", sizes = "512";
  int clustersPerRank = 1;
  std::string workDir = "out/bench", dumpDir, json, markdown, device;
};

std::string countMesh(const CountArgs& a) {
  if (!a.mesh.empty()) return a.mesh;
  return generatedMesh(a.workDir, demoMeshOptions());
}

struct DumpSummary {
  double seconds = 0;
  uint64_t fragments = 0, lostRays = 0;
};

// Renders each of `ranks` virtual ranks' shares of `whole` and writes their counts to `path`.
DumpSummary dumpRealCounts(const vk::Context& ctx, const mesh::UnstructuredMesh& whole,
                           const mesh::Field& field, const render::RenderSettings& settings,
                           int ranks, int clustersPerRank, const std::string& path) {
  Timer t;
  mesh::UnstructuredMesh split = whole;
  const int clusters = ranks * clustersPerRank;
  partition::assignMetisClusters(split, clusters);
  const prep::GlobalFrame frame = prep::makeGlobalFrame(split.bounds());
  comp::CountDumpWriter writer(path, uint32_t(settings.width), uint32_t(settings.height),
                               uint32_t(ranks));
  comp::DeepCompositor compositor(ctx, nullptr, settings.width, settings.height, {});
  DumpSummary out;
  std::vector<uint32_t> counts;
  for (int r = 0; r < ranks; ++r) {
    // Round-robin, as RankGroup deals them: each share is scattered and interlocks with others.
    std::vector<int> mine;
    for (int c = r; c < clusters; c += ranks) mine.push_back(c);
    partition::ExtractedClusters e = partition::extractClustersWithPointMap(split, mine);
    if (e.mesh.numCells() == 0) {  // METIS may leave a cluster empty: this rank renders nothing
      writer.append(std::vector<uint32_t>(size_t(settings.width) * settings.height, 0u));
      continue;
    }
    std::vector<float> values(e.originalPoint.size());
    for (size_t i = 0; i < values.size(); ++i) values[i] = field.steps[0][e.originalPoint[i]];
    prep::PrepResult p = prep::prepareRank(e.mesh, frame, prep::PrepOptions{true});
    render::GpuScene gpu(ctx, p.rank, std::move(p.rank.positions));
    gpu.setScalars(prep::gatherScalars(p.rank, values));
    render::Renderer renderer(ctx, gpu, compositor);
    const render::FrameResult result = renderer.render(settings);
    out.fragments += result.counters.fragments;
    out.lostRays += result.counters.lostRays;
    compositor.downloadCounts(counts);
    writer.append(counts);
    if ((r + 1) % 50 == 0 || r + 1 == ranks)
      std::fprintf(stderr, "bench counts: %d ranks: rendered %d of %d shares (%.0f s)\n", ranks,
                   r + 1, ranks, t.seconds());
  }
  writer.close();
  out.seconds = t.seconds();
  return out;
}

nlohmann::json spreadJson(const comp::ReplayResult& r, uint64_t comp::ReplayRank::*field,
                          double scale = 1.0) {
  double lo = 1e300;
  for (const comp::ReplayRank& k : r.ranks) lo = std::min(lo, double(k.*field) * scale);
  return {{"min", lo}, {"mean", r.mean(field) * scale}, {"max", double(r.maximum(field)) * scale}};
}

nlohmann::json replayRow(const std::string& dump, int ranks, const DumpSummary& d) {
  comp::CountDumpReader reader(dump);
  // The compositor's default ownership, and the paper's contiguous ranges for comparison.
  auto replay = [&](comp::PixelOwnership own) {
    return comp::replayExchange(
        uint64_t(reader.width()) * reader.height(), ranks, comp::Encoding::Float, 0, own,
        [&](int rank, std::vector<uint32_t>& c) { reader.read(uint32_t(rank), c); });
  };
  const comp::ReplayResult r = replay(comp::PixelOwnership::Interleaved);
  const comp::ReplayResult byRanges = replay(comp::PixelOwnership::Ranges);
  const double toRgba8 = double(comp::fragmentBytes(comp::Encoding::Rgba8)) / r.fragmentBytes;
  uint64_t nonEmpty = 0, dumped = 0;
  for (const comp::ReplayRank& k : r.ranks) {
    nonEmpty += k.nonEmptyPixels;
    dumped += k.fragments;
  }
  // The dump is the lists the renderer filled: every fragment it counted is in them.
  if (dumped != d.fragments)
    throw Error(dump, ": holds ", dumped, " fragments, the renderer counted ", d.fragments);
  return {
      {"ranks", ranks},
      {"width", reader.width()},
      {"height", reader.height()},
      {"dump", dump},
      {"render_seconds", d.seconds},
      {"fragments", d.fragments},
      {"lost_rays", d.lostRays},
      {"fragments_per_nonempty_rank_pixel", nonEmpty ? double(d.fragments) / nonEmpty : 0.0},
      {"counter_bits", r.counterBits},
      {"count_bytes_sent", spreadJson(r, &comp::ReplayRank::countBytesSent)},
      {"fragment_bytes_sent_float", spreadJson(r, &comp::ReplayRank::fragmentBytesSent)},
      {"fragment_bytes_sent_rgba8", spreadJson(r, &comp::ReplayRank::fragmentBytesSent, toRgba8)},
      {"fragment_bytes_received_float", spreadJson(r, &comp::ReplayRank::fragmentBytesReceived)},
      {"render_imbalance", r.imbalance(&comp::ReplayRank::fragments)},
      {"composite_imbalance", r.imbalance(&comp::ReplayRank::fragmentsComposited)},
      {"composite_imbalance_ranges", byRanges.imbalance(&comp::ReplayRank::fragmentsComposited)}};
}

void runCountBench(const CountArgs& a) {
  const std::vector<uint64_t> rankCounts = parseCounts("--ranks", a.ranks);
  const std::vector<std::pair<int, int>> sizes = parseSizes("--sizes", a.sizes);
  if (a.clustersPerRank < 1)
    throw Error("--clusters-per-rank: must be at least 1, not ", a.clustersPerRank);
  const std::string path = countMesh(a);
  io::ReadOptions read;
  read.fields = {a.field};
  const mesh::UnstructuredMesh whole = io::readMesh(path, read);
  const mesh::Field* field = whole.findField(a.field);
  if (!field) throw Error("--field: ", path, " has no point field '", a.field, "'");
  for (uint64_t n : rankCounts)
    if (n * uint64_t(a.clustersPerRank) > whole.numCells())
      throw Error("--ranks ", n, ": more clusters than the mesh's ", whole.numCells(), " elements");
  const std::string dumpDir = a.dumpDir.empty() ? a.workDir : a.dumpDir;
  std::filesystem::create_directories(dumpDir);
  vk::ContextOptions co;
  co.device = a.device;
  vk::Context ctx(co);
  nlohmann::json rows = nlohmann::json::array();
  Table table({"ranks", "image", "fragments", "frag/rank px", "bits", "count kB/rank mean", "max",
               "float frag kB/rank mean", "max", "rgba8 mean", "max", "render imbal", "comp imbal",
               "comp imbal ranges", "render s"});
  for (const auto& [w, h] : sizes) {
    // Every virtual rank renders the frame of the whole mesh.
    const render::RenderSettings settings = isoFrame(whole, *field, a.colormap, w, h);
    for (uint64_t n : rankCounts) {
      const std::string dump =
          concat(dumpDir, "/counts-", std::filesystem::path(path).stem().string(), "-", n, "r-", w,
                 "x", h, ".smfcnt");
      const DumpSummary d =
          dumpRealCounts(ctx, whole, *field, settings, int(n), a.clustersPerRank, dump);
      nlohmann::json row = replayRow(dump, int(n), d);
      auto kB = [&](const char* f, const char* s) { return fixed(double(row[f][s]) / 1e3, 1); };
      table.add({std::to_string(n), sizeName(w, h), std::to_string(d.fragments),
                 fixed(double(row["fragments_per_nonempty_rank_pixel"]), 2),
                 std::to_string(int(row["counter_bits"])), kB("count_bytes_sent", "mean"),
                 kB("count_bytes_sent", "max"), kB("fragment_bytes_sent_float", "mean"),
                 kB("fragment_bytes_sent_float", "max"), kB("fragment_bytes_sent_rgba8", "mean"),
                 kB("fragment_bytes_sent_rgba8", "max"), fixed(double(row["render_imbalance"]), 2),
                 fixed(double(row["composite_imbalance"]), 2),
                 fixed(double(row["composite_imbalance_ranges"]), 2), fixed(d.seconds, 0)});
      rows.push_back(std::move(row));
    }
  }
  const std::string text =
      concat("Machine: ", machineLine(machineJson()), "\nMesh: ", path, " (", whole.numCells(),
             " elements), field ", a.field, ", iso view; ", a.clustersPerRank,
             " METIS cluster(s) per virtual rank, dealt round-robin; each rank's share rendered "
             "on ",
             ctx.deviceName(), ", its counts replayed through the exchange\n\n", table.str());
  std::printf("%s", text.c_str());
  if (!a.json.empty())
    writeJsonFile(a.json, {{"benchmark", "counts"},
                           {"machine", machineJson()},
                           {"device", ctx.deviceName()},
                           {"mesh", path},
                           {"rows", rows}});
  if (!a.markdown.empty()) writeTextFile(a.markdown, text);
  checkValidation(ctx);
}

}  // namespace

void configureCountBench(CLI::App& cmd) {
  auto a = std::make_shared<CountArgs>();
  cmd.add_option("--mesh", a->mesh, "Mesh to split (default: the demo capsule, generated once)");
  cmd.add_option("--field", a->field, "Point field (step 0)")
      ->capture_default_str()
      ->check(nonEmptyName());
  cmd.add_option("--colormap", a->colormap, "Colour map")->capture_default_str();
  cmd.add_option("--ranks", a->ranks, "Virtual rank counts, comma separated")
      ->capture_default_str();
  cmd.add_option("--sizes", a->sizes, "Image sizes: N (square) or WxH, comma separated")
      ->capture_default_str();
  cmd.add_option("--clusters-per-rank", a->clustersPerRank,
                 "METIS clusters per virtual rank (dealt round-robin)")
      ->capture_default_str();
  cmd.add_option("--work-dir", a->workDir, "Where the demo mesh is generated once")
      ->capture_default_str();
  cmd.add_option("--dump-dir", a->dumpDir, "Where the count dumps go (default: --work-dir)");
  cmd.add_option("--device", a->device, "Vulkan device index or name substring");
  cmd.add_option("--json", a->json, "Write the results as JSON to this file")
      ->check(writableFile());
  cmd.add_option("--markdown", a->markdown, "Write the table as Markdown to this file");
  cmd.callback([a] { runCountBench(*a); });
}

}  // namespace sm::app::bench
