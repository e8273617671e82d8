// `shellmarch generate`: CFD-like meshes, from gmsh (a capsule or a lander in a far-field box) up
// to a million elements, from the procedural O-grid (app/generate_grid.h) above, or tiny analytic
// meshes; split into clusters, with analytic fields, written as .pvtu.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "cli/generate_grid.h"
#include "common/error.h"
#include "common/file_util.h"
#include "common/timer.h"
#include "gen/generate.h"
#include "io/mesh_io.h"
#include "partition/partition.h"

namespace sm::app {
namespace {

struct GenerateArgs {
  std::string method = "auto";
  std::string body = "capsule";
  uint64_t elements = 300000;
  int clusters = 0;  // 0: 8 for gmsh and analytic meshes, one per ~4 M elements for the grid
  int steps = 1;
  bool hexBlock = false;
  uint64_t seed = 1;
  std::string analytic;
  int cubeN = 4;
  int threads = 1;
  bool cellData = false;
  std::string compress = "auto";
  std::string out;
};

constexpr uint64_t kMinElements = 5000, kMaxElements = 100000000;
// gmsh makes about 14 thousand elements a second (a million in about 70 s); above this `auto` uses
// the grid, which makes millions a second.
constexpr uint64_t kGmshAutoLimit = 1000000;

bool usesGrid(const GenerateArgs& a) {
  return a.analytic.empty() &&
         (a.method == "grid" || (a.method == "auto" && a.elements > kGmshAutoLimit));
}

mesh::UnstructuredMesh analyticMesh(const std::string& kind, int cubeN) {
  using mesh::CellType;
  if (kind == "single-tet") return gen::singleElement(CellType::Tet);
  if (kind == "single-pyramid") return gen::singleElement(CellType::Pyramid);
  if (kind == "single-wedge") return gen::singleElement(CellType::Wedge);
  if (kind == "single-hex") return gen::singleElement(CellType::Hex);
  if (kind == "zoo") return gen::zoo();
  if (auto split = gen::cubeSplitNamed(kind)) return gen::cube(*split, cubeN);
  throw Error("--analytic: unknown mesh '", kind,
              "' (expected single-tet, single-pyramid, single-wedge, single-hex, zoo, cube-tets5, "
              "cube-tets6, cube-wedges, cube-pyramids or cube-hex)");
}

// Option checks that CLI11 cannot express, each naming its option.
void validate(const GenerateArgs& a, const CLI::App& cmd) {
  if (fileExtension(a.out) != ".pvtu" && fileExtension(a.out) != ".pvd")
    throw Error("--out: expected a .pvtu file (or a .pvd time series), got '", a.out, "'");
  if (a.method != "auto" && a.method != "gmsh" && a.method != "grid")
    throw Error("--method: expected auto, gmsh or grid, got '", a.method, "'");
  if (a.compress != "auto" && a.compress != "on" && a.compress != "off")
    throw Error("--compress: expected auto, on or off, got '", a.compress, "'");
  if (cmd.count("--clusters") && a.clusters < 1)
    throw Error("--clusters: must be at least 1, got ", a.clusters);
  // Each step is a field array of the whole mesh, written into every piece: a bound like
  // --elements', before anything is allocated.
  if (a.steps < 1 || a.steps > 10000)
    throw Error("--steps: must be between 1 and 10000, got ", a.steps);
  if (a.threads < 0) throw Error("--threads: must not be negative, got ", a.threads);
  if (a.analytic.empty() && usesGrid(a)) {
    if (fileExtension(a.out) != ".pvtu")
      throw Error("--out: the grid method writes a .pvtu (its steps as arrays), got '", a.out,
                  "'; a .pvd series needs --method gmsh");
    for (const char* gmshOnly : {"--body", "--hex-block", "--threads", "--seed"})
      if (cmd.count(gmshOnly))
        throw Error(gmshOnly, ": applies to gmsh meshes (--method gmsh), not to the grid");
    return;  // the grid checks its own sizes
  }
  if (cmd.count("--method") && !a.analytic.empty())
    throw Error("--method: applies to CFD-like meshes, not to --analytic");
  if (a.analytic.empty()) {
    if (a.body != "capsule" && a.body != "lander")
      throw Error("--body: expected capsule or lander, got '", a.body, "'");
    if (a.elements < kMinElements || a.elements > kMaxElements)
      throw Error("--elements: must be between ", kMinElements, " and ", kMaxElements, ", got ",
                  a.elements);
    if (cmd.count("--cube-n")) throw Error("--cube-n: applies to --analytic cube-* meshes only");
    return;
  }
  for (const char* gmshOnly : {"--body", "--elements", "--hex-block", "--threads"})
    if (cmd.count(gmshOnly)) throw Error(gmshOnly, ": applies to gmsh meshes, not to --analytic");
  if (a.cubeN < 1 || a.cubeN > 1000)
    throw Error("--cube-n: must be between 1 and 1000, got ", a.cubeN);
  if (cmd.count("--cube-n") && a.analytic.rfind("cube-", 0) != 0)
    throw Error("--cube-n: applies to --analytic cube-* meshes only");
  // Bounded like --elements, before anything is allocated: a cube too large for memory would
  // otherwise end in an "out of memory" that names no option.
  const auto split = gen::cubeSplitNamed(a.analytic);  // unknown names: analyticMesh says so
  const uint64_t n = uint64_t(a.cubeN);
  const uint64_t cells = split ? n * n * n * gen::cellsPerCube(*split) : 0;
  if (cells > kMaxElements)
    throw Error("--cube-n: ", a.cubeN, " makes ", cells, " cells of ", a.analytic, ", more than ",
                kMaxElements);
}

std::string summary(const std::string& out, const mesh::UnstructuredMesh& m, double seconds) {
  std::string types;
  for (mesh::CellType t : mesh::kAllCellTypes) {
    if (!types.empty()) types += ", ";
    types += concat(m.numCells(t), " ", mesh::cellTypePluralName(t));
  }
  char time[32];
  std::snprintf(time, sizeof time, "%.1f", seconds);
  uint64_t steps = m.numSteps();
  for (const mesh::CellField& f : m.cellFields) steps = std::max<uint64_t>(steps, f.steps.size());
  return concat("wrote ", out, ": ", m.numCells(), " elements (", types, "), ", m.numClusters(),
                " clusters, ", steps, steps == 1 ? " step" : " steps",
                m.cellFields.empty() ? "" : " of cell data", ", ", time, " s");
}

void runGenerate(const GenerateArgs& a, const CLI::App& cmd) {
  validate(a, cmd);
  if (usesGrid(a)) {
    const std::string line =
        generateGridMesh({a.elements, a.clusters, a.steps, a.cellData, a.compress == "on", a.out});
    std::printf("%s\n", line.c_str());
    return;
  }
  Timer timer;
  mesh::UnstructuredMesh m;
  const int clusters = a.clusters > 0 ? a.clusters : 8;
  if (a.analytic.empty()) {
    gen::CfdMeshOptions o;
    o.body = a.body == "lander" ? gen::Body::Lander : gen::Body::Capsule;
    o.targetElements = a.elements;
    o.clusters = clusters;
    o.steps = a.steps;
    o.hexBlock = a.hexBlock;
    o.seed = a.seed;
    o.threads = a.threads;
    m = gen::generateCfdMesh(o);
  } else {
    m = analyticMesh(a.analytic, a.cubeN);
    partition::assignMetisClusters(m, clusters, a.seed);
    gen::addAnalyticFields(m, a.steps);
  }
  if (a.cellData) mesh::pointFieldsToCells(m);
  io::WriteOptions options;
  options.compress = a.compress != "off";
  if (fileExtension(a.out) == ".pvd")
    io::writePvdSeries(a.out, m, options);  // a .pvtu per step, as solvers write a time series
  else
    io::writePvtu(a.out, m, options);
  std::printf("%s\n", summary(a.out, m, timer.seconds()).c_str());
}

}  // namespace

void registerGenerate(CLI::App& app) {
  auto args = std::make_shared<GenerateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "generate",
      "Write a CFD-like mesh (gmsh, or the procedural grid for large sizes) or an analytic test "
      "mesh, in clusters, as .pvtu");
  cmd->add_option("--method", args->method,
                  "auto: gmsh up to 1000000 elements (about 14 thousand a second, body-fitted "
                  "capsule or lander), the grid above; gmsh; or grid: an O-grid around a cylinder "
                  "(wedge and hexahedral boundary layer, pyramids, tetrahedra), millions of "
                  "elements a second up to 2000000000, written piece by piece")
      ->capture_default_str();
  cmd->add_option("--body", args->body, "capsule or lander (gmsh)")->capture_default_str();
  cmd->add_option("--elements", args->elements,
                  "Target element count (gmsh: within about 25%; grid: a few percent)")
      ->capture_default_str();
  cmd->add_option("--clusters", args->clusters,
                  "Clusters (.pvtu pieces): METIS parts for gmsh and analytic meshes (default 8); "
                  "interlocking bands and one nested part for the grid (default one per 4 M "
                  "elements, at least 8)");
  cmd->add_option("--steps", args->steps, "Time steps of the analytic fields")
      ->capture_default_str();
  cmd->add_flag("--hex-block", args->hexBlock, "Add a block of hexahedra in the wake");
  cmd->add_option("--seed", args->seed, "METIS seed")->capture_default_str();
  cmd->add_option("--analytic", args->analytic,
                  "single-tet|single-pyramid|single-wedge|single-hex|zoo|cube-tets5|cube-tets6|"
                  "cube-wedges|cube-pyramids|cube-hex instead of a gmsh mesh");
  cmd->add_option("--cube-n", args->cubeN, "Cells per side of the cube-* meshes")
      ->capture_default_str();
  cmd->add_option("--threads", args->threads,
                  "gmsh threads (0: all cores; 1 gives bit-identical meshes)")
      ->capture_default_str();
  cmd->add_flag("--cell-data", args->cellData,
                "Write the fields as cell data, each element the mean of its vertices (as "
                "finite-volume solvers write theirs)");
  cmd->add_option("--compress", args->compress,
                  "zlib-compress the arrays: auto (on, except for the grid, which writes raw for "
                  "speed), on or off")
      ->capture_default_str();
  cmd->add_option("--out", args->out,
                  "Output .pvtu (pieces go beside it), or .pvd (a time series: a .pvtu per step)")
      ->required();
  cmd->callback([args, cmd] { runGenerate(*args, *cmd); });
}

}  // namespace sm::app
