// Legacy .vtk reader (DATASET UNSTRUCTURED_GRID), ascii or binary (big-endian), with the cell
// layout of versions up to 4.2 (CELLS n size: counts and ids, 32-bit) and of 5.1 (CELLS with
// OFFSETS and CONNECTIVITY arrays of any integer type). The file is scanned once, keeping views
// of the binary arrays it needs (ascii ones are parsed); the mesh is built at the end.
#include <algorithm>
#include <cctype>

#include "common/error.h"
#include "common/log.h"
#include "io/ghost_cells.h"
#include "io/legacy_scanner.h"
#include "io/polyhedra.h"
#include "io/readers.h"
#include "io_core/array_plan.h"
#include "io_core/numeric_array.h"
#include "io_core/text_scan.h"
#include "mesh/mesh_builder.h"

namespace sm::io {
namespace {

constexpr int64_t kMaxIds = 32;  // ids handed to the builder per cell
constexpr int64_t kPolyhedron = 42;

struct Array {
  std::string name;
  bool identifier = false;
  NumericArray data;
};

enum class Where { Dataset, Points, Cells };

class LegacyReader {
 public:
  LegacyReader(FileBytes& bytes, const std::string& source, const ReadOptions& options)
      : src_(source), options_(options), in_(bytes.span(), source) {}

  mesh::UnstructuredMesh read() {
    readHeader();
    for (std::string_view w = in_.token(); !w.empty(); w = in_.token()) {
      throwIfStopped(options_.stopRequested, src_);
      lastArray_.clear();
      section(lowerCase(w));
      previous_ = lastArray_.empty() ? concat("the ", printable(w), " section") : lastArray_;
    }
    throwIfStopped(options_.stopRequested, src_);
    return build();
  }

 private:
  void readHeader() {
    if (in_.line().rfind("# vtk DataFile Version", 0) != 0)
      throw FileError(src_, "is not a legacy VTK file (no '# vtk DataFile Version' line)");
    in_.line();  // title
    const std::string enc = lowerCase(in_.token());
    if (enc != "ascii" && enc != "binary")
      in_.fail(concat("expected ASCII or BINARY, found '", printable(enc), "'"));
    in_.setBinary(enc == "binary");
    if (!in_.acceptKeyword("dataset")) in_.fail("expected DATASET");
    const std::string type = lowerCase(in_.token());
    if (type != "unstructured_grid")
      throw FileError(src_, "is a legacy ", type.empty() ? "(empty)" : printable(type),
                      " data set; shellmarch reads UNSTRUCTURED_GRID only");
  }

  bool keepCellArray(std::string_view name) const {
    if (name == "vtkGhostType" || askedForAsField(name)) return true;
    if (!options_.clusterArray.empty()) return name == options_.clusterArray;
    return name == "cluster" || name == "partition" || name == "vtkProcessId";
  }

  // A cell array that --field names (itself, a component, or its time steps) may be the field:
  // kept until addFields knows whether a point array of that name came too.
  bool askedForAsField(std::string_view name) const {
    if (!options_.loadFields) return false;
    const std::string base = splitStepName(name).base;
    for (const std::string& r : options_.fields) {
      const auto component = splitComponent(r);
      if (r == base || (component && component->first == base)) return true;
    }
    return false;
  }

  void addArray(Where where, std::string name, std::string_view type, uint32_t comps,
                bool identifier) {
    const std::string what =
        concat(where == Where::Cells ? "cell" : "point", " array '", name, "'");
    const uint64_t tuples = where == Where::Cells ? numCells_ : numPoints_;
    bool keep = where == Where::Points ? options_.loadFields : keepCellArray(name);
    NumericArray a = in_.data(type, comps, tuples, what, keep);
    lastArray_ = what;
    if (!a.data) {
      if (where == Where::Cells) cellArrays_.push_back({std::move(name), identifier, {}});
      return;
    }
    (where == Where::Cells ? cellArrays_ : pointArrays_)
        .push_back({std::move(name), identifier, std::move(a)});
  }

  void fieldSection(Where where) {
    TextCursor head(in_.line());
    head.token();  // the field's name
    const uint64_t nArrays = in_.count(head.token(), "FIELD array count");
    for (uint64_t i = 0; i < nArrays; ++i) {
      if (in_.atEnd()) in_.fail(concat("FIELD: the file ends before array ", i));
      TextCursor fields(in_.line());
      std::string_view first = fields.token();
      if (double v = 0; !lastArray_.empty() && !in_.binary() && parseNumber(first, v))
        in_.fail(concat("FIELD: found the number '", printable(first), "' where array ", i,
                        "'s name should be: ", lastArray_, " holds more values than it declares"));
      if (lowerCase(first) == "null_array") continue;
      std::string name = decodeVtkName(first);
      const uint64_t comps = in_.count(fields.token(), "component count");
      const uint64_t tuples = in_.count(fields.token(), "tuple count");
      std::string_view type = fields.token();
      if (comps == 0 || comps > 4096)
        in_.fail(concat("array '", name, "' has ", comps, " components"));
      if (where == Where::Dataset) {
        bool time = isTimeValuesArray(name);
        lastArray_ = concat("field data '", name, "'");
        NumericArray a = in_.data(type, uint32_t(comps), tuples, lastArray_, time);
        if (time && a.data) timeValues_ = std::move(a);
      } else {
        const uint64_t expected = where == Where::Cells ? numCells_ : numPoints_;
        if (tuples != expected)
          in_.fail(concat("array '", name, "' has ", tuples, " tuples, expected ", expected));
        const bool identifier = isBookkeepingArray(name);
        addArray(where, std::move(name), type, uint32_t(comps), identifier);
      }
      in_.skipMetadataIfPresent();
    }
  }

  void attribute(Where where, const std::string& key) {
    if (where == Where::Dataset) in_.fail(concat(key, " outside POINT_DATA or CELL_DATA"));
    TextCursor l(in_.line());
    std::string name = decodeVtkName(l.token());
    if (key == "lookup_table") {  // a table of colours: size x 4 values
      const uint64_t size = in_.count(l.token(), "LOOKUP_TABLE size");
      in_.data(in_.binary() ? "unsigned_char" : "float", 4, size, "lookup table", false);
      return;
    }
    if (key == "color_scalars") {
      const uint64_t n = in_.count(l.token(), "COLOR_SCALARS component count");
      if (n == 0 || n > 4096) in_.fail("COLOR_SCALARS component count out of range");
      addArray(where, name, in_.binary() ? "unsigned_char" : "float", uint32_t(n), false);
      return;
    }
    uint64_t comps = key == "vectors" || key == "normals" ? 3
                     : key == "tensors"                   ? 9
                     : key == "tensors6"                  ? 6
                                                          : 1;
    if (key == "texture_coordinates") comps = in_.count(l.token(), "texture dimension");
    std::string_view type = l.token();
    if (type.empty()) in_.fail(concat(key, " '", name, "' has no data type"));
    if (key == "scalars") {
      if (std::string_view c = l.token(); !c.empty())
        comps = in_.count(c, "SCALARS component count");
      if (in_.acceptKeyword("lookup_table")) in_.line();  // the table's name
    }
    if (comps == 0 || comps > 4096)
      in_.fail(concat(key, " '", name, "': component count out of range"));
    const bool identifier =
        key == "global_ids" || key == "pedigree_ids" || isBookkeepingArray(name);
    addArray(where, std::move(name), type, uint32_t(comps), identifier);
    in_.skipMetadataIfPresent();
  }

  void section(const std::string& key) {
    if (key == "points") {
      TextCursor l(in_.line());
      numPoints_ = in_.count(l.token(), "POINTS count");
      mesh::checkPointCount(src_, numPoints_, "declares",
                            "split it into the pieces of a .pvtu and use more ranks");
      points_ = in_.data(l.token(), 3, numPoints_, "points", true);
    } else if (key == "cells") {
      cellsSection();
    } else if (key == "cell_types") {
      TextCursor l(in_.line());
      const uint64_t n = in_.count(l.token(), "CELL_TYPES count");
      types_ = in_.data(in_.binary() ? "int" : "vtktypeint64", 1, n, "cell types", true);
      haveTypes_ = true;
    } else if (key == "point_data" || key == "cell_data") {
      TextCursor l(in_.line());
      const uint64_t n = in_.count(l.token(), "data count");
      where_ = key == "point_data" ? Where::Points : Where::Cells;
      const uint64_t expected = where_ == Where::Points ? numPoints_ : numCells_;
      if (n != expected)
        in_.fail(concat(key == "point_data" ? "POINT_DATA " : "CELL_DATA ", n,
                        " does not match the ", expected,
                        where_ == Where::Points ? " points" : " cells"));
    } else if (key == "field") {
      fieldSection(where_);
    } else if (key == "metadata") {
      in_.skipMetadata();
    } else if (key == "scalars" || key == "vectors" || key == "normals" || key == "tensors" ||
               key == "tensors6" || key == "texture_coordinates" || key == "color_scalars" ||
               key == "lookup_table" || key == "global_ids" || key == "pedigree_ids") {
      attribute(where_, key);
    } else if (double v = 0; !in_.binary() && parseNumber(key, v)) {
      // A number where a keyword should be: the section before holds more than it declares.
      in_.fail(concat("found the number '", printable(key), "' where a keyword should be: ",
                      previous_.empty() ? std::string("the header") : previous_,
                      " holds more values than it declares"));
    } else {
      in_.fail(concat("unknown keyword '", printable(key), "'"));
    }
  }

  void cellsSection() {
    TextCursor l(in_.line());
    const uint64_t a = in_.count(l.token(), "CELLS count");
    const uint64_t b = in_.count(l.token(), "CELLS size");
    if (in_.acceptKeyword("offsets")) {  // 5.1: a offsets (cells + 1), b connectivity ids
      TextCursor lo(in_.line());
      offsets_ = in_.data(lo.token(), 1, a, "cell offsets", true);
      if (!in_.acceptKeyword("connectivity")) in_.fail("expected CONNECTIVITY after OFFSETS");
      TextCursor lc(in_.line());
      conn_ = in_.data(lc.token(), 1, b, "cell connectivity", true);
      numCells_ = a > 0 ? a - 1 : 0;
      newLayout_ = true;
    } else {  // up to 4.2: a cells, b ints (a count before each cell's ids)
      conn_ = in_.data(in_.binary() ? "int" : "vtktypeint64", 1, b, "cells", true);
      numCells_ = a;
      newLayout_ = false;
    }
    haveCells_ = true;
  }

  mesh::UnstructuredMesh build();
  template <class T, bool Swap>
  void addCellsOld(mesh::MeshBuilder& b, const std::vector<int64_t>& types,
                   const std::vector<int64_t>& ghost);
  template <class T, bool Swap>
  void addCellsNew(mesh::MeshBuilder& b, const std::vector<int64_t>& offsets,
                   const std::vector<int64_t>& types, const std::vector<int64_t>& ghost);
  void addFields(mesh::MeshBuilder& b);
  void addClusters(mesh::MeshBuilder& b);
  std::vector<std::string> dataCellArrayNames() const;

  const std::string& src_;
  const ReadOptions& options_;
  LegacyScanner in_;
  bool newLayout_ = false, haveCells_ = false, haveTypes_ = false;
  Where where_ = Where::Dataset;
  // What was read last, for messages: "the CELLS section", or the array a FIELD or attribute
  // section ended with, since a count one off there is the array's and not the section's.
  std::string previous_, lastArray_;
  uint64_t numPoints_ = 0, numCells_ = 0;
  GhostCells ghostCells_;
  NumericArray points_, conn_, offsets_, types_, timeValues_;
  std::vector<int64_t> stream_;  // a polyhedron's face stream (reused)
  std::vector<Array> pointArrays_, cellArrays_;
};

// Cells as a list of (count, ids...) records, read where they lie.
template <class T, bool Swap>
void LegacyReader::addCellsOld(mesh::MeshBuilder& b, const std::vector<int64_t>& types,
                               const std::vector<int64_t>& ghost) {
  const uint64_t size = conn_.numValues();
  auto at = [&](uint64_t i) {
    return static_cast<int64_t>(loadAs<T, Swap>(conn_.data + i * sizeof(T)));
  };
  int64_t ids[kMaxIds];
  uint64_t pos = 0;
  for (uint64_t c = 0; c < numCells_; ++c) {
    if (pos >= size) throw FileError(src_, "CELLS: the list ends before cell ", c);
    const int64_t n = at(pos);
    if (n < 0 || uint64_t(n) > size - pos - 1)
      throw FileError(src_, "CELLS: cell ", c, " claims ", n, " points, past the end of the list");
    if (ghostCells_.skip(ghost, c)) {
    } else if (types[c] == kPolyhedron) {
      // The record after its count is the cell's face stream.
      stream_.resize(size_t(n));
      for (int64_t k = 0; k < n; ++k) stream_[size_t(k)] = at(pos + 1 + k);
      b.addPolyhedron(facesFromStream(stream_, src_, c, numPoints_), c);
    } else {
      const int64_t m = std::min(n, kMaxIds);
      for (int64_t k = 0; k < m; ++k) ids[k] = at(pos + 1 + k);
      b.addVtkCell(static_cast<int>(std::clamp<int64_t>(types[c], -1, 1 << 20)), {ids, size_t(m)},
                   c);
    }
    pos += 1 + uint64_t(n);
  }
}

template <class T, bool Swap>
void LegacyReader::addCellsNew(mesh::MeshBuilder& b, const std::vector<int64_t>& offsets,
                               const std::vector<int64_t>& types,
                               const std::vector<int64_t>& ghost) {
  int64_t ids[kMaxIds];
  auto id = [&](int64_t i) {
    T v = loadAs<T, Swap>(conn_.data + i * sizeof(T));
    if constexpr (std::is_unsigned_v<T>)
      return v > T(INT64_MAX) ? INT64_MAX : static_cast<int64_t>(v);
    else
      return static_cast<int64_t>(v);
  };
  for (uint64_t c = 0; c < numCells_; ++c) {
    if (ghostCells_.skip(ghost, c)) continue;
    if (types[c] == kPolyhedron) {  // its connectivity is its face stream
      stream_.resize(size_t(offsets[c + 1] - offsets[c]));
      for (size_t i = 0; i < stream_.size(); ++i) stream_[i] = id(offsets[c] + int64_t(i));
      b.addPolyhedron(facesFromStream(stream_, src_, c, numPoints_), c);
      continue;
    }
    const int64_t begin = offsets[c], n = std::min(offsets[c + 1] - begin, kMaxIds);
    for (int64_t i = 0; i < n; ++i) ids[i] = id(begin + i);
    b.addVtkCell(static_cast<int>(std::clamp<int64_t>(types[c], -1, 1 << 20)), {ids, size_t(n)}, c);
  }
}

std::vector<std::string> LegacyReader::dataCellArrayNames() const {
  std::vector<std::string> names;
  for (const auto& a : cellArrays_) names.push_back(a.name);
  return dataCellArrays(names, options_);
}

void LegacyReader::addClusters(mesh::MeshBuilder& b) {
  std::vector<std::string> names;
  for (const auto& a : cellArrays_) names.push_back(a.name);
  auto chosen = chooseClusterArray(src_, names, options_);
  if (!chosen) return;
  const Array& a = cellArrays_[*chosen];
  if (a.data.components != 1)
    throw FileError(src_, "cell array '", a.name, "' has ", a.data.components,
                    " components; cluster ids need 1");
  b.setClusterIds(toInt64(a.data, src_, concat("cell array '", a.name, "'")), a.name);
}

void LegacyReader::addFields(mesh::MeshBuilder& b) {
  std::vector<ArrayInfo> infos, cellInfos;
  for (const auto& a : pointArrays_) infos.push_back({a.name, a.data.components, a.identifier});
  for (const auto& a : cellArrays_) cellInfos.push_back({a.name, a.data.components, a.identifier});
  const FieldSplit split = splitFieldRequests(infos, cellInfos, options_);
  ArrayName array;  // names the array toFloats reads, for its precision warning
  for (const FieldLoad& load : planFields(src_, cellInfos, split.cells, nullptr, "cell")) {
    if (cellArrays_[load.array].data.tuples != numCells_)
      throw FileError(src_, "cell array '", cellArrays_[load.array].name, "' does not have ",
                      numCells_, " values");
    b.addCellFieldStep(load.field, load.step,
                       toFloats(cellArrays_[load.array].data, load.component, options_.threads,
                                &(array = {src_, "cell", cellArrays_[load.array].name})));
  }
  const std::vector<std::string> cellData = dataCellArrayNames();
  for (const FieldLoad& load : planFields(src_, infos, split.points, &cellData))
    b.addFieldStep(load.field, load.step,
                   toFloats(pointArrays_[load.array].data, load.component, options_.threads,
                            &(array = {src_, "point", pointArrays_[load.array].name})));
}

mesh::UnstructuredMesh LegacyReader::build() {
  mesh::MeshBuilder b(src_);
  if (numPoints_ > 0 && !points_.data) throw FileError(src_, "has no POINTS");
  if (numPoints_ > 0) b.setPoints(toPoints(points_, options_.threads));
  if (haveCells_ != haveTypes_)
    throw FileError(src_,
                    haveCells_ ? "has CELLS but no CELL_TYPES" : "has CELL_TYPES but no CELLS");
  if (haveCells_) {
    if (types_.numValues() != numCells_)
      throw FileError(src_, "CELL_TYPES lists ", types_.numValues(), " cells, CELLS ", numCells_);
    const std::vector<int64_t> types = toInt64(types_, src_, "cell types");
    b.setFileCells(numCells_);  // origins are kept for polyhedra (their cell data's means)
    std::vector<int64_t> ghost;
    for (const auto& a : cellArrays_)
      if (a.name == "vtkGhostType" && a.data.data) ghost = toInt64(a.data, src_, "vtkGhostType");
    // CELL_DATA sized the array for the CELLS before it; a later CELLS section may differ.
    if (!ghost.empty() && ghost.size() != numCells_)
      throw FileError(src_, "vtkGhostType has ", ghost.size(), " values for ", numCells_, " cells");
    if (isFloatType(conn_.type)) throw FileError(src_, "cell ids must be integers");
    if (!newLayout_) {
      visitArray(conn_, [&](auto tag, auto swap) {
        using T = typename decltype(tag)::type;
        if constexpr (std::is_same_v<T, int32_t> || std::is_same_v<T, int64_t>)
          addCellsOld<T, decltype(swap)::value>(b, types, ghost);
      });
    } else {
      const std::vector<int64_t> offsets = toInt64(offsets_, src_, "cell offsets");
      if (offsets.empty() || offsets[0] != 0) throw FileError(src_, "cell offsets must start at 0");
      for (size_t i = 1; i < offsets.size(); ++i)
        if (offsets[i] < offsets[i - 1])
          throw FileError(src_, "cell offsets decrease at cell ", i - 1);
      if (uint64_t(offsets.back()) != conn_.numValues())
        throw FileError(src_, "cell offsets end at ", offsets.back(), " but CONNECTIVITY has ",
                        conn_.numValues(), " ids");
      visitArray(conn_, [&](auto tag, auto swap) {
        using T = typename decltype(tag)::type;
        if constexpr (std::is_integral_v<T>)
          addCellsNew<T, decltype(swap)::value>(b, offsets, types, ghost);
      });
    }
  }
  ghostCells_.warn(src_);
  b.setCellArrays(dataCellArrayNames());
  addClusters(b);
  if (options_.loadFields) addFields(b);
  if (timeValues_.data) {
    std::vector<double> t(timeValues_.numValues());
    visitArray(timeValues_, [&](auto tag, auto swap) {
      using T = typename decltype(tag)::type;
      for (size_t i = 0; i < t.size(); ++i)
        t[i] = double(loadAs<T, decltype(swap)::value>(timeValues_.data + i * sizeof(T)));
    });
    b.setTimeValues(std::move(t));
  }
  return b.finish();
}

}  // namespace

mesh::UnstructuredMesh readLegacyVtk(FileBytes bytes, const std::string& source,
                                     const ReadOptions& options) {
  return LegacyReader(bytes, source, options).read();
}

}  // namespace sm::io
