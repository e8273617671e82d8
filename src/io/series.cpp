#include "io/series.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>
#include <pugixml.hpp>

#include "common/check.h"
#include "common/error.h"
#include "common/file_util.h"
#include "io/readers.h"
#include "io/series_same_mesh.h"
#include "io_core/file_bytes.h"

namespace sm::io {
namespace {

std::string describeTime(double t) {
  return concat(t);
}

std::vector<SeriesStep> pvdSteps(const std::string& path, const std::string& text) {
  pugi::xml_document doc;
  const pugi::xml_parse_result ok = doc.load_buffer(text.data(), text.size());
  if (!ok) throw FileError(path, "is not well-formed XML (", ok.description(), ")");
  pugi::xml_node root = doc.child("VTKFile");
  if (!root || std::string_view(root.attribute("type").value()) != "Collection")
    throw FileError(path, "is not a ParaView data collection (<VTKFile type=\"Collection\">)");
  pugi::xml_node collection = root.child("Collection");
  if (!collection) throw FileError(path, "has no <Collection> element");
  std::vector<SeriesStep> steps;
  for (pugi::xml_node set : collection.children("DataSet")) {
    const std::string file = set.attribute("file").value();
    if (file.empty()) throw FileError(path, "data set ", steps.size(), " has no file attribute");
    SeriesStep s{joinPath(directoryOf(path), file), double(steps.size())};
    if (pugi::xml_attribute t = set.attribute("timestep")) {
      // The whole value, spaces around it aside, in decimal or exponent form (no hex, no units).
      std::string_view v = t.value();
      while (!v.empty() && std::isspace(static_cast<unsigned char>(v.front()))) v.remove_prefix(1);
      while (!v.empty() && std::isspace(static_cast<unsigned char>(v.back()))) v.remove_suffix(1);
      auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), s.time);
      if (v.empty() || ec != std::errc() || end != v.data() + v.size())
        throw FileError(path, "data set '", file, "' has timestep \"", t.value(),
                        "\", not a number");
    }
    steps.push_back(std::move(s));
  }
  return steps;
}

std::vector<SeriesStep> jsonSteps(const std::string& path, const std::string& text) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw FileError(path, "is not valid JSON (", e.what(), ")");
  }
  if (!j.is_object() || !j.contains("files") || !j["files"].is_array())
    throw FileError(path, "is not a file series (a JSON object with a \"files\" array)");
  std::vector<SeriesStep> steps;
  for (const nlohmann::json& f : j["files"]) {
    if (!f.is_object() || !f.contains("name") || !f["name"].is_string())
      throw FileError(path, "entry ", steps.size(), " of \"files\" has no \"name\" string");
    SeriesStep s{joinPath(directoryOf(path), f["name"].get<std::string>()), double(steps.size())};
    if (f.contains("time")) {
      if (!f["time"].is_number())
        throw FileError(path, "entry '", f["name"].get<std::string>(),
                        "' has a \"time\" that is not a number");
      s.time = f["time"].get<double>();
    }
    steps.push_back(std::move(s));
  }
  return steps;
}

void checkSteps(const std::string& path, std::vector<SeriesStep>& steps) {
  if (steps.empty()) throw FileError(path, "names no files");
  for (const SeriesStep& s : steps) {
    if (!std::isfinite(s.time))
      throw FileError(path, "file '", s.file, "' has time ", describeTime(s.time),
                      ", not a finite number");
    if (isSeries(s.file)) throw FileError(path, "names another series ('", s.file, "')");
    if (fileExtension(s.file) != fileExtension(steps[0].file))
      throw FileError(path, "mixes formats: '", steps[0].file, "' and '", s.file,
                      "' (every step must be the same kind of file)");
  }
  std::stable_sort(steps.begin(), steps.end(),
                   [](const SeriesStep& a, const SeriesStep& b) { return a.time < b.time; });
  for (size_t i = 1; i < steps.size(); ++i)
    if (steps[i].time == steps[i - 1].time)
      throw FileError(path, "time ", describeTime(steps[i].time), " has two files ('",
                      steps[i - 1].file, "' and '", steps[i].file,
                      "'); shellmarch reads one mesh per time step (join parts as the pieces "
                      "of a .pvtu)");
}

std::string stepName(uint64_t k, const SeriesStep& s) {
  return concat("step ", k, " ('", s.file, "')");
}

// A file of a series holds one step of each field.
void checkOneStep(const std::string& path, uint64_t k, const SeriesStep& s,
                  const std::string& field, uint64_t steps) {
  if (steps > 1)
    throw FileError(path, stepName(k, s), " holds field '", field, "' with ", steps,
                    " time steps; in a series each file holds one step");
}

DeclaredSize total(const std::vector<DeclaredSize>& pieces) {
  DeclaredSize t;
  for (const DeclaredSize& p : pieces) t.points += p.points, t.cells += p.cells;
  return t;
}

// Step k's file holds the mesh of step 0, by the sizes its headers declare for each piece read
// (the geometry is not read): pieces of the same sizes in the same order.
void checkSameSizes(const std::string& path, const std::vector<SeriesStep>& steps, uint64_t k,
                    const ReadOptions& options, const std::vector<DeclaredSize>& first) {
  const std::vector<DeclaredSize> mine = declaredSizes(steps[k].file, options);
  if (mine == first) return;
  const DeclaredSize a = total(mine), b = total(first);
  if (a != b)
    throw FileError(path, stepName(k, steps[k]), " has ", a.points, " points and ", a.cells,
                    " cells, step 0 ('", steps[0].file, "') ", b.points, " and ", b.cells,
                    ": every step of a series must be the same mesh");
  if (mine.size() != first.size())
    throw FileError(path, stepName(k, steps[k]), " has ", mine.size(), " pieces, step 0 ('",
                    steps[0].file, "') ", first.size(),
                    ": every step of a series must be the same mesh, in the same pieces");
  size_t i = 0;
  while (mine[i] == first[i]) ++i;
  std::vector<int> chosen = options.pieces;
  std::sort(chosen.begin(), chosen.end());
  throw FileError(path, stepName(k, steps[k]), " piece ", chosen.empty() ? int(i) : chosen[i],
                  " has ", mine[i].points, " points and ", mine[i].cells, " cells, that of step 0 ",
                  first[i].points, " and ", first[i].cells,
                  ": every step of a series must be the same mesh, its pieces in the same order");
}

// What every later step of a .vtu or .pvtu series is checked against.
struct FirstStep {
  std::vector<DeclaredSize> sizes;
  std::vector<FieldStepCount> fields;
};

FirstStep firstStep(const std::string& path, const std::vector<SeriesStep>& steps,
                    const ReadOptions& options) {
  FirstStep f{declaredSizes(steps[0].file, options), listFieldSteps(steps[0].file, options)};
  for (const FieldStepCount& c : f.fields) checkOneStep(path, 0, steps[0], c.name, c.steps);
  return f;
}

// Step k of a .vtu or .pvtu series, from its headers: step 0's mesh, and each of step 0's fields
// with one step.
void checkStep(const std::string& path, const std::vector<SeriesStep>& steps, uint64_t k,
               const ReadOptions& options, const FirstStep& first) {
  checkSameSizes(path, steps, k, options, first.sizes);
  const std::vector<FieldStepCount> fields = listFieldSteps(steps[k].file, options);
  for (const FieldStepCount& f : first.fields) {
    auto it = std::find_if(fields.begin(), fields.end(),
                           [&](const FieldStepCount& c) { return c.name == f.name; });
    if (it == fields.end())
      throw FileError(path, stepName(k, steps[k]), " has no field '", f.name, "'");
    if (it->cellData != f.cellData)
      throw FileError(path, stepName(k, steps[k]), " holds '", f.name, "' as ",
                      it->cellData ? "cell" : "point", " data, step 0 as ",
                      f.cellData ? "cell" : "point", " data");
    // A vector where step 0 has a scalar (or another vector) would be read as its magnitude and
    // drawn with step 0's transfer function: refused, as within one file.
    if (it->components && f.components && it->components != f.components)
      throw FileError(path, stepName(k, steps[k]), " holds '", f.name, "' with ", it->components,
                      " components, step 0 with ", f.components);
    checkOneStep(path, k, steps[k], f.name, it->steps);
  }
}

// One value per element, type after type, as a cell field's step holds them.
std::array<std::vector<float>, mesh::kNumCellTypes> byType(const mesh::UnstructuredMesh& m,
                                                           const std::vector<float>& flat) {
  std::array<std::vector<float>, mesh::kNumCellTypes> out;
  size_t at = 0;
  for (int t = 0; t < mesh::kNumCellTypes; ++t) {
    const size_t n = m.numCells(mesh::kAllCellTypes[t]);
    SM_CHECK_LE(at + n, flat.size());
    out[t].assign(flat.begin() + at, flat.begin() + at + n);
    at += n;
  }
  return out;
}

void appendStep(const std::string& path, uint64_t k, const SeriesStep& s, mesh::UnstructuredMesh& m,
                mesh::UnstructuredMesh next) {
  if (next.numPoints() != m.numPoints() || next.numCells() != m.numCells())
    throw FileError(path, stepName(k, s), " has ", next.numPoints(), " points and ",
                    next.numCells(), " cells, step 0 ", m.numPoints(), " and ", m.numCells(),
                    ": every step of a series must be the same mesh");
  checkSameMesh(path, k, s, stepMeshOf(m), stepMeshOf(next));
  for (mesh::Field& f : m.fields) {
    auto g = std::find_if(next.fields.begin(), next.fields.end(),
                          [&](const mesh::Field& p) { return p.name == f.name; });
    if (g == next.fields.end())
      throw FileError(path, stepName(k, s), " has no point field '", f.name, "'");
    checkOneStep(path, k, s, f.name, g->numSteps());
    f.steps.push_back(std::move(g->steps[0]));
  }
  for (mesh::CellField& f : m.cellFields) {
    auto g = std::find_if(next.cellFields.begin(), next.cellFields.end(),
                          [&](const mesh::CellField& c) { return c.name == f.name; });
    if (g == next.cellFields.end())
      throw FileError(path, stepName(k, s), " has no cell field '", f.name, "'");
    checkOneStep(path, k, s, f.name, g->steps.size());
    f.steps.push_back(std::move(g->steps[0]));
  }
}

}  // namespace

bool isSeries(const std::string& path) {
  const std::string ext = fileExtension(path);
  return ext == ".pvd" || ext == ".series";
}

std::vector<SeriesStep> readSeriesIndex(const std::string& path) {
  // A stream asks for the index at every frame, and loading asks several times: the last index
  // read is kept while its file is unchanged (same size and modification time).
  struct Cached {
    std::string path;
    std::filesystem::file_time_type time;
    uintmax_t size = 0;
    std::vector<SeriesStep> steps;
  };
  static std::mutex mutex;
  static Cached cached;
  std::error_code ec;
  const auto time = std::filesystem::last_write_time(path, ec);
  const uintmax_t size = ec ? 0 : std::filesystem::file_size(path, ec);
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (!ec && cached.path == path && cached.time == time && cached.size == size)
      return cached.steps;
  }
  const std::string text = FileBytes::readPrefix(path, size_t(1) << 28);
  std::vector<SeriesStep> steps =
      fileExtension(path) == ".pvd" ? pvdSteps(path, text) : jsonSteps(path, text);
  checkSteps(path, steps);
  if (!ec) {
    std::lock_guard<std::mutex> lock(mutex);
    cached = {path, time, size, steps};
  }
  return steps;
}

mesh::UnstructuredMesh readSeries(const std::string& path, const ReadOptions& options,
                                  const ReadStepFile& readStep) {
  const std::vector<SeriesStep> steps = readSeriesIndex(path);
  ReadOptions one = options;
  one.step.reset();
  if (options.step) {  // that step's file alone (a later step than the last: the last, as a field)
    const uint64_t k = std::min<uint64_t>(*options.step, steps.size() - 1);
    if (k > 0 && readsStepsAlone(steps[k].file))
      checkSameSizes(path, steps, k, options, declaredSizes(steps[0].file, options));
    mesh::UnstructuredMesh m = readStep(steps[k].file, one);
    for (const mesh::Field& f : m.fields) checkOneStep(path, k, steps[k], f.name, f.numSteps());
    for (const mesh::CellField& f : m.cellFields)
      checkOneStep(path, k, steps[k], f.name, f.steps.size());
    // Every step's time, as a .vtu read for one step keeps its TimeValues: what the caller needs
    // to tell steps by time.
    m.timeValues.clear();
    for (const SeriesStep& step : steps) m.timeValues.push_back(step.time);
    return m;
  }
  // Steps with headers (.vtu, .pvtu) are read array by array: each later file's arrays of the
  // fields asked for, point data in the first file's point order and cell data in its element
  // order (which the first read keeps), after the file's headers are checked against the first.
  const bool byArray = readsStepsAlone(steps[0].file);
  ReadOptions first = one;
  first.cellOrigins = first.cellOrigins || byArray;
  mesh::UnstructuredMesh m = readStep(steps[0].file, first);
  for (const mesh::Field& f : m.fields) checkOneStep(path, 0, steps[0], f.name, f.numSteps());
  for (const mesh::CellField& f : m.cellFields)
    checkOneStep(path, 0, steps[0], f.name, f.steps.size());
  const FirstStep firstSizes = byArray ? firstStep(path, steps, one) : FirstStep{};
  for (uint64_t k = 1; k < steps.size(); ++k) {
    if (!byArray) {  // formats without headers to go by: each step's whole file
      appendStep(path, k, steps[k], m, readStep(steps[k].file, one));
      continue;
    }
    checkStep(path, steps, k, one, firstSizes);
    checkSameMesh(path, steps, k, one);
    for (mesh::Field& f : m.fields)
      f.steps.push_back(readFieldStep(steps[k].file, f.name, 0, one, m.pointOrigin));
    for (mesh::CellField& f : m.cellFields)
      f.steps.push_back(byType(m, readCellFieldStep(steps[k].file, f.name, 0, one, m.cellOrigin)));
  }
  if (!options.cellOrigins) {
    std::vector<uint32_t>().swap(m.cellOrigin);
    m.fileCells = 0;
  }
  m.timeValues.clear();
  for (const SeriesStep& s : steps) m.timeValues.push_back(s.time);
  return m;
}

std::vector<FieldStepCount> seriesFieldSteps(const std::string& path, const ReadOptions& options) {
  const std::vector<SeriesStep> steps = readSeriesIndex(path);
  if (!readsStepsAlone(steps[0].file)) {  // read whole: listing step 0 reads it all
    std::vector<FieldStepCount> fields = listFieldSteps(steps[0].file, options);
    for (FieldStepCount& f : fields) {
      checkOneStep(path, 0, steps[0], f.name, f.steps);
      f.steps = steps.size();
    }
    return fields;
  }
  // Before anything renders from the listing (a stream reads step k only when its frame comes):
  // every step's file is there, holds step 0's mesh and fields, one step each, by its headers.
  FirstStep first = firstStep(path, steps, options);
  for (uint64_t k = 1; k < steps.size(); ++k) checkStep(path, steps, k, options, first);
  for (FieldStepCount& f : first.fields) f.steps = steps.size();
  return first.fields;
}

namespace {

// Step `step`'s file, its sizes checked again from its headers (every step's headers were checked
// when the series was listed, io::listFieldSteps), so that a step replaced since reads as an
// error.
const SeriesStep& checkedStepFile(const std::string& path, const std::string& field, uint64_t step,
                                  const ReadOptions& options,
                                  const std::vector<SeriesStep>& steps) {
  if (step >= steps.size())
    throw FileError(path, "field '", field, "' has ", steps.size(), " time steps (0 .. ",
                    steps.size() - 1, "), not step ", step);
  if (step > 0 && readsStepsAlone(steps[step].file))
    checkSameSizes(path, steps, step, options, declaredSizes(steps[0].file, options));
  checkSameMesh(path, steps, step, options);
  return steps[step];
}

}  // namespace

std::vector<float> seriesFieldStep(const std::string& path, const std::string& field, uint64_t step,
                                   const ReadOptions& options, std::span<const uint32_t> pointMap) {
  const std::vector<SeriesStep> steps = readSeriesIndex(path);
  if (step < steps.size() && !readsStepsAlone(steps[step].file)) {
    // A file read whole gives its mesh with its field: checked from the same parse.
    auto check = [&](const mesh::UnstructuredMesh& m) {
      checkSameMesh(path, steps, step, options, stepMeshOf(m));
    };
    return wholeReadFieldStep(steps[step].file, field, 0, options, pointMap, check);
  }
  return readFieldStep(checkedStepFile(path, field, step, options, steps).file, field, 0, options,
                       pointMap);
}

std::vector<float> seriesCellFieldStep(const std::string& path, const std::string& field,
                                       uint64_t step, const ReadOptions& options,
                                       std::span<const uint32_t> cellMap) {
  const std::vector<SeriesStep> steps = readSeriesIndex(path);
  return readCellFieldStep(checkedStepFile(path, field, step, options, steps).file, field, 0,
                           options, cellMap);
}

}  // namespace sm::io
