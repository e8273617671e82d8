// Time steps without the mesh: which fields a file has and how many steps each (from the XML
// headers), and one step of one field decoded on its own. A time series is streamed this way, one
// step in memory at a time, instead of every step being loaded with the mesh.
#include <algorithm>
#include <map>
#include <optional>

#include "common/error.h"
#include "common/file_util.h"
#include "io/mesh_io.h"
#include "io/readers.h"
#include "io/series.h"
#include "io/vtu_arrays.h"
#include "io/vtu_document.h"
#include "io_core/array_plan.h"
#include "io_core/numeric_array.h"
#include "solver_io/pieced_readers.h"

namespace sm::io {
namespace {

// Fields in the order the loads name them first (the order readMesh adds them in), each with its
// step count and the components of the arrays (of `arrays`) it is read from; a gap in the steps is
// the error a full read gives.
std::vector<FieldStepCount> countSteps(const std::string& source,
                                       const std::vector<FieldLoad>& loads,
                                       const std::vector<ArrayInfo>& arrays) {
  std::vector<FieldStepCount> fields;
  std::vector<std::vector<uint64_t>> steps;
  for (const FieldLoad& l : loads) {
    auto it = std::find_if(fields.begin(), fields.end(),
                           [&](const FieldStepCount& f) { return f.name == l.field; });
    if (it == fields.end()) {
      // One component of an array ("p[1]") reads whatever the array's count: not compared.
      fields.push_back(
          {l.field, 0, false, l.component < 0 ? uint32_t(arrays.at(l.array).components) : 0u});
      steps.emplace_back();
      it = fields.end() - 1;
    }
    steps[it - fields.begin()].push_back(l.step);
  }
  for (size_t f = 0; f < fields.size(); ++f) {
    std::sort(steps[f].begin(), steps[f].end());
    for (uint64_t i = 0; i < steps[f].size(); ++i)
      if (steps[f][i] != i)
        throw FileError(source, "point field '", fields[f].name, "' has no values for time step ",
                        i);
    fields[f].steps = steps[f].size();
  }
  return fields;
}

// Every step of every field options ask for (ReadOptions::step narrows loads, not the listing).
std::vector<FieldLoad> planAllSteps(const std::string& source, const std::vector<ArrayInfo>& arrays,
                                    const ReadOptions& options,
                                    const std::vector<std::string>* cellData,
                                    std::string_view kind = "point") {
  if (!options.loadFields) return {};
  ReadOptions all = options;
  all.step.reset();
  return planFields(source, arrays, all, cellData, kind);
}

std::vector<FieldStepCount> vtuFieldSteps(const std::string& file, const ReadOptions& options) {
  FileBytes bytes = FileBytes::openLazily(file);
  VtuDocument doc(bytes, file, "UnstructuredGrid", options.threads);
  std::vector<VtuPiece> pieces = vtuPieces(doc);
  const std::vector<ArrayInfo> points = vtuPointArrays(doc, pieces[0]);
  if (options.fields.empty() || !options.loadFields) {  // every point array; no cell data
    ReadOptions all = options;
    all.loadFields = true;
    return countSteps(file, planAllSteps(file, points, all, nullptr), points);
  }
  // Cell data named as a field is a field readMesh loads too (averaged onto the points).
  const std::vector<ArrayInfo> cells = vtuCellArrays(doc, pieces[0]);
  const FieldSplit split = splitFieldRequests(points, cells, options);
  const std::vector<std::string> cellData = dataCellArrays(vtuCellArrayNames(pieces[0]), options);
  std::vector<FieldStepCount> steps =
      countSteps(file, planAllSteps(file, points, split.points, &cellData), points);
  if (split.cells.loadFields)
    for (FieldStepCount& f :
         countSteps(file, planAllSteps(file, cells, split.cells, nullptr, "cell"), cells)) {
      f.cellData = true;
      steps.push_back(std::move(f));
    }
  return steps;
}

// The pieces read together are welded, which needs the same fields and steps in each; and a
// field must be the same quantity in each (a vector's magnitude in one piece and a scalar in
// another would join without a seam, a wrong image with no error).
void checkSameSteps(const std::string& path, const std::string& piece,
                    const std::vector<FieldStepCount>& first,
                    const std::vector<FieldStepCount>& other, const std::string& firstPiece) {
  for (const FieldStepCount& f : first) {
    auto it = std::find_if(other.begin(), other.end(),
                           [&](const FieldStepCount& o) { return o.name == f.name; });
    if (it == other.end())
      throw FileError(path, "piece '", piece, "' has no point field '", f.name, "'");
    if (it->cellData != f.cellData)
      throw FileError(path, "piece '", piece, "' holds '", f.name, "' as ",
                      it->cellData ? "cell" : "point", " data, the first piece as ",
                      f.cellData ? "cell" : "point", " data");
    if (it->steps != f.steps)
      throw FileError(path, "piece '", piece, "' has ", it->steps, " time steps of field '", f.name,
                      "', the first piece ", f.steps);
    if (it->components != f.components && it->components != 0 && f.components != 0)
      throw FileError(path, "piece '", piece, "' has ", it->components, " components in field '",
                      f.name, "', the first piece ('", firstPiece, "') ", f.components,
                      ": every piece must hold a field alike");
  }
  if (other.size() != first.size())
    throw FileError(path, "piece '", piece, "' has ", other.size(),
                    " point fields, the first piece ", first.size());
}

// The components a .pvtu declares for each field of its point or cell data (<PPointData>,
// <PCellData>; the steps "NAME@tK" of one field under NAME), where it declares them. Every rank
// reads the index, so pieces checked against it agree across ranks without talking.
std::map<std::string, uint32_t> declaredComponents(const std::string& path, bool cells) {
  std::map<std::string, uint32_t> out;
  if (fileExtension(path) != ".pvtu") return out;
  FileBytes bytes = FileBytes::openLazily(path);
  VtuDocument doc(bytes, path, "PUnstructuredGrid");
  const pugi::xml_node data =
      doc.root().child("PUnstructuredGrid").child(cells ? "PCellData" : "PPointData");
  for (pugi::xml_node a : data.children("PDataArray"))
    out.emplace(splitStepName(a.attribute("Name").value()).base,
                doc.components(a, concat("array '", a.attribute("Name").value(), "'")));
  return out;
}

std::vector<FieldStepCount> pvtuFieldSteps(const std::string& path, const ReadOptions& options) {
  const std::vector<std::string> files = pvtuPieceFiles(path);
  const std::map<std::string, uint32_t> declared[2] = {declaredComponents(path, false),
                                                       declaredComponents(path, true)};
  std::vector<FieldStepCount> first;
  std::string firstFile;
  for (int i : choosePieces(path, files.size(), options)) {
    std::vector<FieldStepCount> steps = vtuFieldSteps(files[i], options);
    for (const FieldStepCount& f : steps) {
      auto d = declared[f.cellData].find(f.name);
      if (f.components != 0 && d != declared[f.cellData].end() && d->second != f.components)
        throw FileError(path, "piece '", files[i], "' has ", f.components, " components in field '",
                        f.name, "', the index declares ", d->second,
                        ": every piece must hold a field alike");
    }
    if (firstFile.empty()) {
      first = std::move(steps);
      firstFile = files[i];
    } else {
      checkSameSteps(path, files[i], first, steps, firstFile);
    }
  }
  return first;
}

std::vector<FieldStepCount> stepsOfMesh(const mesh::UnstructuredMesh& m) {
  std::vector<FieldStepCount> fields;
  for (const mesh::Field& f : m.fields) fields.push_back({f.name, f.numSteps()});
  return fields;
}

// Where a field's values sit: one per point, or one per cell.
enum class Data { Points, Cells };

std::vector<float> vtuFieldStep(const std::string& file, const std::string& field, uint64_t step,
                                const ReadOptions& options, Data data) {
  throwIfStopped(options.stopRequested, file);
  FileBytes bytes = FileBytes::openLazily(file);
  VtuDocument doc(bytes, file, "UnstructuredGrid", options.threads, options.stopRequested);
  std::vector<VtuPiece> pieces = vtuPieces(doc);
  const bool cells = data == Data::Cells;
  const std::vector<ArrayInfo> pointArrays = vtuPointArrays(doc, pieces[0]);
  const std::vector<ArrayInfo> cellArrays = vtuCellArrays(doc, pieces[0]);
  ReadOptions one;
  one.fields = {field};
  // As readMesh decides: point data when the points hold the name, else cell data. A name held
  // by neither is named as missing below.
  const bool inPoints = holdsField(pointArrays, field);
  if ((inPoints || holdsField(cellArrays, field)) && inPoints == cells)
    throw FileError(file, "holds '", field, "' as ", inPoints ? "point" : "cell", " data, not ",
                    cells ? "cell" : "point",
                    " data (every step, and every piece of a .pvtu, must hold it alike)");
  const std::vector<ArrayInfo>& arrays = cells ? cellArrays : pointArrays;
  const char* kind = cells ? "cell" : "point";
  const std::vector<FieldLoad> loads = planFields(file, arrays, one, nullptr, kind);
  auto load =
      std::find_if(loads.begin(), loads.end(), [&](const FieldLoad& l) { return l.step == step; });
  if (load == loads.end())
    throw FileError(file, "has no ", kind, " array '",
                    splitStepName(arrays[loads[0].array].name).base, "@t", step, "' (field '",
                    field, "' has ", loads.size(),
                    loads.size() == 1 ? " time step)" : " time steps)");
  const ArrayInfo& info = arrays[load->array];
  const std::string what = concat(kind, " array '", info.name, "'");
  const ArrayName name{file, kind, info.name};
  std::vector<float> values;
  for (const VtuPiece& p : pieces) {
    pugi::xml_node a = findDataArray(p.node.child(cells ? "CellData" : "PointData"), info.name);
    if (!a) throw FileError(file, "a piece lacks the ", what);
    std::vector<float> v =
        toFloats(doc.decode(a, cells ? p.numCells : p.numPoints, what, info.components),
                 load->component, options.threads, &name);
    values.insert(values.end(), v.begin(), v.end());
  }
  return values;
}

std::vector<float> pvtuFieldStep(const std::string& path, const std::string& field, uint64_t step,
                                 const ReadOptions& options, Data data) {
  const std::vector<std::string> files = pvtuPieceFiles(path);
  std::vector<float> values;
  for (int i : choosePieces(path, files.size(), options)) {
    std::vector<float> v = vtuFieldStep(files[i], field, step, options, data);
    values.insert(values.end(), v.begin(), v.end());
  }
  return values;
}

// Formats without random access to one array: the whole file, keeping one field.
std::vector<float> mapValues(const std::string& path, std::vector<float> values,
                             std::span<const uint32_t> map, Data data) {
  if (map.empty()) return values;
  std::vector<float> out(map.size());
  for (size_t i = 0; i < map.size(); ++i) {
    if (map[i] >= values.size())
      throw FileError(path, "has ", values.size(), data == Data::Cells ? " cells" : " points",
                      " in the pieces read, fewer than when its mesh was read");
    out[i] = values[map[i]];
  }
  return out;
}

// The point and cell arrays of the first piece of a .vtu, a .pvtu or a series' first file, from
// its XML header; none for formats without one.
struct FirstPieceArrays {
  std::vector<ArrayInfo> points, cells;
};
std::optional<FirstPieceArrays> firstPieceArrays(const std::string& path,
                                                 const ReadOptions& options) {
  if (isSeries(path)) return firstPieceArrays(readSeriesIndex(path).at(0).file, options);
  if (fileExtension(path) != ".vtu" && !isPieceIndex(path)) return std::nullopt;
  const std::string file = isPieceIndex(path) ? pvtuPieceFiles(path).at(0) : path;
  FileBytes bytes = FileBytes::openLazily(file);
  VtuDocument doc(bytes, file, "UnstructuredGrid", options.threads);
  const std::vector<VtuPiece> pieces = vtuPieces(doc);
  return FirstPieceArrays{vtuPointArrays(doc, pieces.at(0)), vtuCellArrays(doc, pieces.at(0))};
}

}  // namespace

std::vector<float> wholeReadFieldStep(
    const std::string& path, const std::string& field, uint64_t step, const ReadOptions& options,
    std::span<const uint32_t> pointMap,
    const std::function<void(const mesh::UnstructuredMesh&)>& check) {
  ReadOptions o = options;
  o.fields = {field};
  o.loadFields = true;
  o.step.reset();
  mesh::UnstructuredMesh m = readMesh(path, o);
  if (check) check(m);
  mesh::Field* f = m.fields.empty() ? nullptr : &m.fields[0];
  if (!f || step >= f->numSteps())
    throw FileError(path, "point field '", field, "' has ", f ? f->numSteps() : 0,
                    " time steps, not step ", step);
  return mapValues(path, std::move(f->steps[step]), pointMap, Data::Points);
}

std::vector<FieldStepCount> listFieldSteps(const std::string& path, const ReadOptions& options) {
  const std::string ext = fileExtension(path);
  if (ext == ".vtu") return vtuFieldSteps(path, options);
  if (isPieceIndex(path)) return pvtuFieldSteps(path, options);
  if (isSeries(path)) return seriesFieldSteps(path, options);
  if (const std::optional<PiecedFormat> f = piecedFormatOf(path))
    return piecedFieldSteps(path, piecedLayout(*f, path), options);
  ReadOptions o = options;
  o.step.reset();
  o.loadFields = true;
  return stepsOfMesh(readMesh(path, o));
}

std::vector<float> readFieldStep(const std::string& path, const std::string& field, uint64_t step,
                                 const ReadOptions& options, std::span<const uint32_t> pointMap) {
  const std::string ext = fileExtension(path);
  std::vector<float> values;
  if (ext == ".vtu")
    values = vtuFieldStep(path, field, step, options, Data::Points);
  else if (isPieceIndex(path))
    values = pvtuFieldStep(path, field, step, options, Data::Points);
  else if (isSeries(path))
    return seriesFieldStep(path, field, step, options, pointMap);
  else if (const std::optional<PiecedFormat> f = piecedFormatOf(path))
    values = piecedFieldStep(*f, path, field, step, options);
  else
    return wholeReadFieldStep(path, field, step, options, pointMap);
  return mapValues(path, std::move(values), pointMap, Data::Points);
}

std::vector<float> readCellFieldStep(const std::string& path, const std::string& field,
                                     uint64_t step, const ReadOptions& options,
                                     std::span<const uint32_t> cellMap) {
  std::vector<float> values;
  if (fileExtension(path) == ".vtu")
    values = vtuFieldStep(path, field, step, options, Data::Cells);
  else if (isPieceIndex(path))
    values = pvtuFieldStep(path, field, step, options, Data::Cells);
  else if (isSeries(path))
    return seriesCellFieldStep(path, field, step, options, cellMap);
  else
    throw Error(path,
                ": cell data is read one step at a time from .vtu and .pvtu files and "
                "series of them only");
  return mapValues(path, std::move(values), cellMap, Data::Cells);
}

std::vector<std::string> listCellData(const std::string& path, const ReadOptions& options) {
  if (const std::optional<PiecedFormat> f = piecedFormatOf(path)) {
    std::vector<std::string> names;
    for (const FieldStepCount& c : piecedLayout(*f, path).fields)
      if (c.cellData) names.push_back(c.name);
    return names;
  }
  const std::optional<FirstPieceArrays> arrays = firstPieceArrays(path, options);
  std::vector<std::string> names;
  if (arrays)
    for (const ArrayInfo& a : arrays->cells)
      if (!a.identifier) names.push_back(a.name);
  return dataCellArrays(names, options);
}

bool asksForCellData(const std::string& path, const ReadOptions& options) {
  if (options.fields.empty() || !options.loadFields) return false;
  if (const std::optional<PiecedFormat> f = piecedFormatOf(path)) {
    for (const FieldStepCount& c : piecedFieldSteps(path, piecedLayout(*f, path), options))
      if (c.cellData) return true;
    return false;
  }
  const std::optional<FirstPieceArrays> arrays = firstPieceArrays(path, options);
  return arrays && splitFieldRequests(arrays->points, arrays->cells, options).cells.loadFields;
}

}  // namespace sm::io
