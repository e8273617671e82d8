// `shellmarch info FILE`: what a mesh file holds as shellmarch reads it (element counts, skipped
// and fixed cells, clusters, fields with their steps and ranges, bounds), in words or as exactly
// one JSON object on stdout. Reader warnings go to stderr, so --json output stays parseable.
#include <algorithm>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/cli_checks.h"
#include "cli/commands.h"
#include "common/error.h"
#include "io/mesh_io.h"

namespace sm::app {
namespace {

using mesh::CellType;

struct InfoOptions {
  std::string file;
  bool json = false;
  std::vector<std::string> fields;
  std::string clusterArray;
  std::vector<int> pieces;
};

// Cells of each cluster id; empty when the ids are too sparse to list (a file may number its
// clusters up to 2^31 - 1).
std::vector<uint64_t> cellsPerCluster(const mesh::UnstructuredMesh& m) {
  const uint64_t n = uint64_t(std::max(m.numClusters(), 0));
  if (n > 2 * m.numCells() + 4096) return {};
  std::vector<uint64_t> count(n);
  for (const auto& c : m.clusters)
    for (int32_t id : c) ++count[id];
  return count;
}

nlohmann::json rangeJson(const mesh::Range& r) {
  return r.empty ? nlohmann::json(nullptr) : nlohmann::json::array({r.lo, r.hi});
}

// Components of the array each field is read from (by name): 1 for a scalar, N for a vector
// shown as its magnitude, 0 for one component asked for ("v[1]"). Known from the XML headers as
// readMesh planned its reads (or the format's headers); not for legacy .vtk and .ugrid files,
// which would be parsed again.
using Components = std::map<std::string, uint32_t>;

Components componentsOf(const InfoOptions& o, const io::ReadOptions& read) {
  Components out;
  if (!io::listsFieldsFromHeaders(o.file)) return out;
  for (const io::FieldStepCount& f : io::listFieldSteps(o.file, read)) out[f.name] = f.components;
  return out;
}

std::optional<uint32_t> componentCount(const Components& c, const std::string& name) {
  auto it = c.find(name);
  return it == c.end() ? std::nullopt : std::optional(it->second);
}

nlohmann::json infoJson(const InfoOptions& o, const mesh::UnstructuredMesh& m,
                        const Components& components) {
  nlohmann::json j;
  j["file"] = o.file;
  j["format"] = io::formatDescription(o.file);
  j["pieces"] = io::countPieces(o.file);
  j["points"] = m.numPoints();
  j["tets"] = m.numCells(CellType::Tet);
  j["pyramids"] = m.numCells(CellType::Pyramid);
  j["wedges"] = m.numCells(CellType::Wedge);
  j["hexes"] = m.numCells(CellType::Hex);
  j["cells"] = m.numCells();
  j["skipped"] = {{"surface", m.skipped.surface},
                  {"lineOrVertex", m.skipped.lineOrVertex},
                  {"polyhedra", m.skipped.polyhedra},
                  {"other", m.skipped.other},
                  {"total", m.skipped.totalSkipped()}};
  j["quadraticReduced"] = m.skipped.quadraticReduced;
  j["polyhedraSplit"] = {{"polyhedra", m.skipped.polyhedraSplit},
                         {"tets", m.skipped.polyhedronTets}};
  j["invertedFixed"] = m.invertedFixed;
  j["clusters"] = m.numClusters();
  const std::vector<uint64_t> per = cellsPerCluster(m);
  j["cellsPerCluster"] =
      per.empty() && m.numCells() ? nlohmann::json(nullptr) : nlohmann::json(per);
  const mesh::Bounds b = m.bounds();
  j["bounds"] =
      b.empty ? nlohmann::json(nullptr)
              : nlohmann::json{{"lo", {b.lo.x, b.lo.y, b.lo.z}}, {"hi", {b.hi.x, b.hi.y, b.hi.z}}};
  j["timeValues"] = m.timeValues;
  j["cellArrays"] = m.cellArrays;  // fields only when named (averaged onto the points)
  j["fields"] = nlohmann::json::array();
  for (const mesh::Field& f : m.fields) {
    const std::optional<uint32_t> count = componentCount(components, f.name);
    j["fields"].push_back({{"name", f.name},
                           {"steps", f.numSteps()},
                           {"components", count ? nlohmann::json(*count) : nlohmann::json()},
                           {"range", rangeJson(mesh::fieldRange(f))}});
  }
  return j;
}

void printText(std::ostream& out, const InfoOptions& o, const mesh::UnstructuredMesh& m,
               const Components& components) {
  auto row = [&out](const char* label, const auto& value) {
    out << "  " << label << std::string(18 - std::string(label).size(), ' ') << value << "\n";
  };
  out << o.file << ": " << io::formatDescription(o.file);
  if (int n = io::countPieces(o.file); n > 1) out << ", " << n << " pieces";
  out << "\n";
  row("points", m.numPoints());
  for (CellType t : mesh::kAllCellTypes)
    row(std::string(mesh::cellTypePluralName(t)).c_str(), m.numCells(t));
  const mesh::SkippedCells& s = m.skipped;
  row("skipped cells",
      s.totalSkipped() == 0
          ? std::string("none")
          : concat(s.totalSkipped(), " (2D ", s.surface, ", vertex/line ", s.lineOrVertex,
                   ", polyhedra ", s.polyhedra, ", other ", s.other, ")"));
  row("quadratic cells", concat(s.quadraticReduced, " reduced to their corners"));
  if (s.polyhedraSplit)
    row("polyhedra", concat(s.polyhedraSplit, " split into ", s.polyhedronTets, " tetrahedra"));
  row("inverted cells", concat(m.invertedFixed, " fixed"));
  const std::vector<uint64_t> per = cellsPerCluster(m);
  std::string clusters = concat(m.numClusters());
  if (per.size() > 1)
    clusters += concat(" (", *std::min_element(per.begin(), per.end()), " to ",
                       *std::max_element(per.begin(), per.end()), " cells each)");
  row("clusters", clusters);
  // Of what renders: the points that elements use.
  const mesh::Bounds b = m.bounds();
  row("bounds", b.empty ? std::string("none (no volume elements)")
                        : concat("x [", b.lo.x, ", ", b.hi.x, "]  y [", b.lo.y, ", ", b.hi.y,
                                 "]  z [", b.lo.z, ", ", b.hi.z, "]"));
  if (!m.timeValues.empty()) {
    std::string t;
    for (double v : m.timeValues) t += (t.empty() ? "" : ", ") + concat(v);
    row("time values", t);
  }
  row("fields", m.fields.size());
  for (const mesh::Field& f : m.fields) {
    const mesh::Range r = mesh::fieldRange(f);
    // Names come from the file: printed as one printable line each, as messages are.
    const uint32_t all = componentCount(components, f.name).value_or(1);
    const uint32_t n = all > 1 ? all : 0;
    // A vector renders as its magnitude: say so, with the names that render one component.
    const std::string magnitude =
        n ? concat("the magnitude of ", n, " components (", printableLine(f.name), "[0] .. ",
                   printableLine(f.name), "[", n - 1, "] for one), ")
          : std::string();
    out << "    " << printableLine(f.name) << ": " << magnitude << f.numSteps()
        << (f.numSteps() == 1 ? " step" : " steps") << ", range "
        << (r.empty ? std::string("none (no finite values)") : concat("[", r.lo, ", ", r.hi, "]"))
        << "\n";
  }
  std::string names;  // cell data not asked for (--field NAME averages it onto the points)
  for (const auto& n : m.cellArrays) {
    const bool loaded = std::any_of(m.fields.begin(), m.fields.end(), [&](const mesh::Field& f) {
      return f.name == n || f.name.rfind(n + "[", 0) == 0;  // itself or a component
    });
    if (!loaded) names += (names.empty() ? "" : ", ") + n;
  }
  if (!names.empty())
    row("cell data", printableLine(names) + " (--field NAME renders it, averaged to the points)");
}

void runInfo(const InfoOptions& o) {
  io::ReadOptions read;
  read.fields = o.fields;
  read.clusterArray = o.clusterArray;
  read.pieces = o.pieces;
  const mesh::UnstructuredMesh m = io::readMesh(o.file, read);
  const Components components = componentsOf(o, read);
  if (o.json)
    std::cout << infoJson(o, m, components).dump(2) << std::endl;
  else
    printText(std::cout, o, m, components);
}

}  // namespace

std::string infoJsonText(const std::string& file) {
  InfoOptions o;
  o.file = file;
  const io::ReadOptions read;
  const mesh::UnstructuredMesh m = io::readMesh(o.file, read);
  return infoJson(o, m, componentsOf(o, read)).dump();
}

void registerInfo(CLI::App& app) {
  auto o = std::make_shared<InfoOptions>();
  CLI::App* sub =
      app.add_subcommand("info", "Describe a mesh file: cells, clusters, fields, bounds");
  sub->add_option("file", o->file,
                  "Mesh file (.vtu, .pvtu, .vtm, .vtk, .ugrid; time series as .pvd or .series)")
      ->required();
  sub->add_flag("--json", o->json, "Print one JSON object instead of text");
  sub->add_option("--field", o->fields,
                  "Field to load, NAME or NAME[k]; cell data is averaged onto the points "
                  "(repeatable; default: every point field)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->check(nonEmptyName());
  sub->add_option("--cluster-array", o->clusterArray, "Cell array holding cluster ids")
      ->check(nonEmptyName());
  sub->add_option("--pieces", o->pieces, ".pvtu pieces to read, e.g. 0,3 (default: all)")
      ->delimiter(',');
  sub->callback([o] { runInfo(*o); });
}

}  // namespace sm::app
