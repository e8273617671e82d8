// Legacy .vtk reader (DATASET UNSTRUCTURED_GRID), ascii or binary (big-endian), with the cell
// layout of versions up to 4.2 (CELLS n size: counts and ids, 32-bit) and of 5.1 (CELLS with
// OFFSETS and CONNECTIVITY arrays of any integer type). The file is scanned once, keeping views
// of the binary arrays it needs (ascii ones are parsed); the mesh is built at the end.
#include <algorithm>
#include <cctype>

#include "common/error.h"
#include "common/log.h"
#include "io/array_plan.h"
#include "io/numeric_array.h"
#include "io/readers.h"
#include "io/text_scan.h"
#include "mesh/mesh_builder.h"

namespace sm::io {
namespace {

constexpr int64_t kMaxIds = 32;        // ids handed to the builder per cell
constexpr int64_t kDuplicateCell = 1;  // vtkGhostType flag of cells owned elsewhere
constexpr uint64_t kMaxValues = uint64_t(1) << 58;

std::string lower(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return r;
}

// VTK writes spaces and unprintable characters of names as %XX.
std::string decodeName(std::string_view s) {
  std::string r;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && std::isxdigit(static_cast<unsigned char>(s[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(s[i + 2]))) {
      r += static_cast<char>(std::stoi(std::string(s.substr(i + 1, 2)), nullptr, 16));
      i += 2;
    } else {
      r += s[i];
    }
  }
  return r;
}

struct Array {
  std::string name;
  bool identifier = false;
  NumericArray data;
};

enum class Where { Dataset, Points, Cells };

class LegacyReader {
 public:
  LegacyReader(FileBytes& bytes, const std::string& source, const ReadOptions& options)
      : src_(source),
        options_(options),
        cur_(reinterpret_cast<const char*>(bytes.data()),
             reinterpret_cast<const char*>(bytes.data()) + bytes.size()) {}

  mesh::UnstructuredMesh read() {
    readHeader();
    for (std::string_view w = cur_.token(); !w.empty(); w = cur_.token()) section(lower(w));
    return build();
  }

 private:
  [[noreturn]] void fail(std::string_view what) const {
    throw FileError(src_, what, " (at byte ", offset(), ")");
  }
  size_t offset() const { return static_cast<size_t>(cur_.pos() - begin_); }

  std::string_view line() {
    const char* b = cur_.pos();
    const char* e = std::find(b, cur_.end(), '\n');
    cur_.setPos(e == cur_.end() ? e : e + 1);
    std::string_view l(b, static_cast<size_t>(e - b));
    while (!l.empty() && isSpace(l.back())) l.remove_suffix(1);
    return l;
  }

  uint64_t number(std::string_view tok, std::string_view what) const {
    uint64_t v = 0;
    if (!parseNumber(tok, v) || v > kMaxValues)
      fail(concat(what, " '", printable(tok), "' is not a count"));
    return v;
  }

  void readHeader() {
    begin_ = cur_.pos();
    std::string_view first = line();
    if (first.rfind("# vtk DataFile Version", 0) != 0)
      throw FileError(src_, "is not a legacy VTK file (no '# vtk DataFile Version' line)");
    line();  // title
    std::string enc = lower(cur_.token());
    if (enc != "ascii" && enc != "binary")
      fail(concat("expected ASCII or BINARY, found '", printable(enc), "'"));
    binary_ = enc == "binary";
    if (lower(cur_.token()) != "dataset") fail("expected DATASET");
    std::string type = lower(cur_.token());
    if (type != "unstructured_grid")
      throw FileError(src_, "is a legacy ", type.empty() ? "(empty)" : printable(type),
                      " data set; shellmarch reads UNSTRUCTURED_GRID only");
  }

  // The data of one array, right after its header line: a view of the file when binary (legacy
  // binary is big-endian), parsed when ascii and `keep`, else skipped.
  NumericArray data(std::string_view typeName, uint32_t comps, uint64_t tuples,
                    const std::string& what, bool keep) {
    std::string t = lower(typeName);
    if (comps == 0 || tuples > kMaxValues / comps) fail(concat(what, ": impossible size"));
    const uint64_t n = tuples * comps;
    if (t == "bit") return bits(n, comps, tuples, what, keep);
    if (t == "string" || t == "utf8_string") {
      skipStrings(n, what);
      return {};
    }
    auto type = scalarTypeFromLegacy(t);
    if (!type) fail(concat(what, ": unknown data type '", typeName, "'"));
    if (binary_) {
      const uint64_t bytes = n * scalarSize(*type);
      if (bytes > cur_.remaining())
        fail(concat(what, ": needs ", bytes, " bytes but the file ends after ", cur_.remaining()));
      const uint8_t* p = reinterpret_cast<const uint8_t*>(cur_.pos());
      cur_.setPos(cur_.pos() + bytes);
      return NumericArray::view(*type, comps, tuples, p, needsSwap(true));
    }
    if (n > maxNumbersInText(cur_.remaining()))
      fail(concat(what, ": declares ", n, " values but the file is too short for them"));
    if (!keep) {
      for (uint64_t i = 0; i < n; ++i)
        if (cur_.token().empty())
          fail(concat(what, ": the file ends after ", i, " of ", n, " values"));
      return {};
    }
    ByteBuffer buf = ByteBuffer::allocate(std::max<uint64_t>(n, 1) * 8);
    ScalarType stored = isFloatType(*type)            ? ScalarType::Float64
                        : *type == ScalarType::UInt64 ? ScalarType::UInt64
                                                      : ScalarType::Int64;
    if (stored == ScalarType::Float64)
      scanNumbers(cur_, reinterpret_cast<double*>(buf.data()), n, src_, what);
    else if (stored == ScalarType::UInt64)
      scanNumbers(cur_, reinterpret_cast<uint64_t*>(buf.data()), n, src_, what);
    else
      scanNumbers(cur_, reinterpret_cast<int64_t*>(buf.data()), n, src_, what);
    return NumericArray::owned(stored, comps, tuples, std::move(buf), false);
  }

  // Bit arrays: packed most significant bit first when binary, 0/1 tokens when ascii.
  NumericArray bits(uint64_t n, uint32_t comps, uint64_t tuples, const std::string& what,
                    bool keep) {
    const uint64_t bytes = binary_ ? (n + 7) / 8 : 0;
    if (binary_ ? bytes > cur_.remaining() : n > maxNumbersInText(cur_.remaining()))
      fail(concat(what, ": the file is too short for ", n, " bits"));
    ByteBuffer buf = ByteBuffer::allocate(std::max<uint64_t>(n, 1));
    const char* p = cur_.pos();
    for (uint64_t i = 0; i < n; ++i) {
      if (binary_) {
        buf.data()[i] = (static_cast<uint8_t>(p[i / 8]) >> (7 - i % 8)) & 1;
      } else {
        std::string_view tok = cur_.token();
        if (tok.empty()) fail(concat(what, ": the file ends inside a bit array"));
        buf.data()[i] = tok != "0";
      }
    }
    if (binary_) cur_.setPos(p + bytes);
    if (!keep) return {};
    return NumericArray::owned(ScalarType::UInt8, comps, tuples, std::move(buf), false);
  }

  // String arrays: one per line in ascii; in binary each string has a big-endian length whose
  // top two bits of the first byte say its width (11: 6 bits, 10: 14 bits, 01: 30 bits, 00: 8
  // bytes).
  void skipStrings(uint64_t n, const std::string& what) {
    for (uint64_t i = 0; i < n; ++i) {
      if (!binary_) {
        if (cur_.remaining() == 0) fail(concat(what, ": the file ends inside a string array"));
        line();
        continue;
      }
      if (cur_.remaining() < 1) fail(concat(what, ": the file ends inside a string array"));
      const uint8_t* p = reinterpret_cast<const uint8_t*>(cur_.pos());
      const int width = (p[0] & 0xC0) == 0xC0   ? 1
                        : (p[0] & 0xC0) == 0x80 ? 2
                        : (p[0] & 0xC0) == 0x40 ? 4
                                                : 8;
      if (cur_.remaining() < size_t(width))
        fail(concat(what, ": the file ends inside a string array"));
      uint64_t len = p[0] & (width == 8 ? 0xFF : 0x3F);
      for (int k = 1; k < width; ++k) len = (len << 8) | p[k];
      if (len > cur_.remaining() - width)
        fail(concat(what, ": a string runs past the end of the file"));
      cur_.setPos(cur_.pos() + width + len);
    }
  }

  void skipMetadata() {
    line();  // rest of the METADATA line
    while (cur_.remaining() > 0 && !line().empty()) {
    }
  }

  bool keepCellArray(std::string_view name) const {
    if (name == "vtkGhostType") return true;
    if (!options_.clusterArray.empty()) return name == options_.clusterArray;
    return name == "cluster" || name == "partition" || name == "vtkProcessId";
  }

  void addArray(Where where, std::string name, std::string_view type, uint32_t comps,
                bool identifier) {
    const std::string what =
        concat(where == Where::Cells ? "cell" : "point", " array '", name, "'");
    const uint64_t tuples = where == Where::Cells ? numCells_ : numPoints_;
    bool keep = where == Where::Points ? options_.loadFields : keepCellArray(name);
    NumericArray a = data(type, comps, tuples, what, keep);
    if (!a.data) {
      if (where == Where::Cells) cellArrays_.push_back({std::move(name), identifier, {}});
      return;
    }
    (where == Where::Cells ? cellArrays_ : pointArrays_)
        .push_back({std::move(name), identifier, std::move(a)});
  }

  void fieldSection(Where where) {
    TextCursor head(line());
    head.token();  // the field's name
    const uint64_t nArrays = number(head.token(), "FIELD array count");
    for (uint64_t i = 0; i < nArrays; ++i) {
      cur_.skipSpace();
      if (cur_.remaining() == 0) fail(concat("FIELD: the file ends before array ", i));
      TextCursor fields(line());
      std::string_view first = fields.token();
      if (lower(first) == "null_array") continue;
      std::string name = decodeName(first);
      const uint64_t comps = number(fields.token(), "component count");
      const uint64_t tuples = number(fields.token(), "tuple count");
      std::string_view type = fields.token();
      if (comps == 0 || comps > 4096) fail(concat("array '", name, "' has ", comps, " components"));
      if (where == Where::Dataset) {
        bool time = isTimeValuesArray(name);
        NumericArray a =
            data(type, uint32_t(comps), tuples, concat("field data '", name, "'"), time);
        if (time && a.data) timeValues_ = std::move(a);
      } else {
        const uint64_t expected = where == Where::Cells ? numCells_ : numPoints_;
        if (tuples != expected)
          fail(concat("array '", name, "' has ", tuples, " tuples, expected ", expected));
        const bool identifier = isBookkeepingArray(name);
        addArray(where, std::move(name), type, uint32_t(comps), identifier);
      }
      skipMetadataIfPresent();
    }
  }

  void skipMetadataIfPresent() {
    const char* save = cur_.pos();
    if (lower(cur_.token()) == "metadata")
      skipMetadata();
    else
      cur_.setPos(save);
  }

  void attribute(Where where, const std::string& key) {
    if (where == Where::Dataset) fail(concat(key, " outside POINT_DATA or CELL_DATA"));
    TextCursor l(line());
    std::string name = decodeName(l.token());
    if (key == "lookup_table") {  // a table of colours: size x 4 values
      const uint64_t size = number(l.token(), "LOOKUP_TABLE size");
      data(binary_ ? "unsigned_char" : "float", 4, size, "lookup table", false);
      return;
    }
    if (key == "color_scalars") {
      const uint64_t n = number(l.token(), "COLOR_SCALARS component count");
      if (n == 0 || n > 4096) fail("COLOR_SCALARS component count out of range");
      addArray(where, name, binary_ ? "unsigned_char" : "float", uint32_t(n), false);
      return;
    }
    uint64_t comps = key == "vectors" || key == "normals" ? 3
                     : key == "tensors"                   ? 9
                     : key == "tensors6"                  ? 6
                                                          : 1;
    if (key == "texture_coordinates") comps = number(l.token(), "texture dimension");
    std::string_view type = l.token();
    if (type.empty()) fail(concat(key, " '", name, "' has no data type"));
    if (key == "scalars") {
      if (std::string_view c = l.token(); !c.empty()) comps = number(c, "SCALARS component count");
      const char* save = cur_.pos();
      if (lower(cur_.token()) == "lookup_table")
        line();  // the table's name
      else
        cur_.setPos(save);
    }
    if (comps == 0 || comps > 4096)
      fail(concat(key, " '", name, "': component count out of range"));
    const bool identifier =
        key == "global_ids" || key == "pedigree_ids" || isBookkeepingArray(name);
    addArray(where, std::move(name), type, uint32_t(comps), identifier);
    skipMetadataIfPresent();
  }

  void section(const std::string& key) {
    if (key == "points") {
      TextCursor l(line());
      numPoints_ = number(l.token(), "POINTS count");
      points_ = data(l.token(), 3, numPoints_, "points", true);
    } else if (key == "cells") {
      cellsSection();
    } else if (key == "cell_types") {
      TextCursor l(line());
      const uint64_t n = number(l.token(), "CELL_TYPES count");
      types_ = data(binary_ ? "int" : "vtktypeint64", 1, n, "cell types", true);
      haveTypes_ = true;
    } else if (key == "point_data" || key == "cell_data") {
      TextCursor l(line());
      const uint64_t n = number(l.token(), "data count");
      where_ = key == "point_data" ? Where::Points : Where::Cells;
      const uint64_t expected = where_ == Where::Points ? numPoints_ : numCells_;
      if (n != expected)
        fail(concat(key == "point_data" ? "POINT_DATA " : "CELL_DATA ", n, " does not match the ",
                    expected, where_ == Where::Points ? " points" : " cells"));
    } else if (key == "field") {
      fieldSection(where_);
    } else if (key == "metadata") {
      skipMetadata();
    } else if (key == "scalars" || key == "vectors" || key == "normals" || key == "tensors" ||
               key == "tensors6" || key == "texture_coordinates" || key == "color_scalars" ||
               key == "lookup_table" || key == "global_ids" || key == "pedigree_ids") {
      attribute(where_, key);
    } else {
      fail(concat("unknown keyword '", printable(key), "'"));
    }
  }

  void cellsSection() {
    TextCursor l(line());
    const uint64_t a = number(l.token(), "CELLS count");
    const uint64_t b = number(l.token(), "CELLS size");
    const char* save = cur_.pos();
    if (lower(cur_.token()) == "offsets") {  // 5.1: a offsets (cells + 1), b connectivity ids
      TextCursor lo(line());
      offsets_ = data(lo.token(), 1, a, "cell offsets", true);
      if (lower(cur_.token()) != "connectivity") fail("expected CONNECTIVITY after OFFSETS");
      TextCursor lc(line());
      conn_ = data(lc.token(), 1, b, "cell connectivity", true);
      numCells_ = a > 0 ? a - 1 : 0;
      newLayout_ = true;
    } else {  // up to 4.2: a cells, b ints (a count before each cell's ids)
      cur_.setPos(save);
      conn_ = data(binary_ ? "int" : "vtktypeint64", 1, b, "cells", true);
      numCells_ = a;
      newLayout_ = false;
    }
    haveCells_ = true;
  }

  mesh::UnstructuredMesh build();
  void addCellsOld(mesh::MeshBuilder& b, const std::vector<int64_t>& types,
                   const std::vector<int64_t>& ghost);
  template <class T, bool Swap>
  void addCellsNew(mesh::MeshBuilder& b, const std::vector<int64_t>& offsets,
                   const std::vector<int64_t>& types, const std::vector<int64_t>& ghost);
  bool skipGhost(const std::vector<int64_t>& ghost, uint64_t c) {
    if (ghost.empty() || !(ghost[c] & kDuplicateCell)) return false;
    ++ghostCells_;
    return true;
  }
  void addFields(mesh::MeshBuilder& b);
  void addClusters(mesh::MeshBuilder& b);

  const std::string& src_;
  const ReadOptions& options_;
  TextCursor cur_;
  const char* begin_ = nullptr;
  bool binary_ = false, newLayout_ = false, haveCells_ = false, haveTypes_ = false;
  Where where_ = Where::Dataset;
  uint64_t numPoints_ = 0, numCells_ = 0, ghostCells_ = 0;
  NumericArray points_, conn_, offsets_, types_, timeValues_;
  std::vector<Array> pointArrays_, cellArrays_;
};

void LegacyReader::addCellsOld(mesh::MeshBuilder& b, const std::vector<int64_t>& types,
                               const std::vector<int64_t>& ghost) {
  const std::vector<int64_t> list = toInt64(conn_, src_, "cells");
  int64_t ids[kMaxIds];
  uint64_t pos = 0;
  for (uint64_t c = 0; c < numCells_; ++c) {
    if (pos >= list.size()) throw FileError(src_, "CELLS: the list ends before cell ", c);
    const int64_t n = list[pos];
    if (n < 0 || uint64_t(n) > list.size() - pos - 1)
      throw FileError(src_, "CELLS: cell ", c, " claims ", n, " points, past the end of the list");
    if (!skipGhost(ghost, c)) {
      const int64_t m = std::min(n, kMaxIds);
      std::copy(list.begin() + pos + 1, list.begin() + pos + 1 + m, ids);
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
  for (uint64_t c = 0; c < numCells_; ++c) {
    const int64_t begin = offsets[c], n = std::min(offsets[c + 1] - begin, kMaxIds);
    if (skipGhost(ghost, c)) continue;
    for (int64_t i = 0; i < n; ++i) {
      T v = loadAs<T, Swap>(conn_.data + (begin + i) * sizeof(T));
      if constexpr (std::is_unsigned_v<T>)
        ids[i] = v > T(INT64_MAX) ? INT64_MAX : static_cast<int64_t>(v);
      else
        ids[i] = static_cast<int64_t>(v);
    }
    b.addVtkCell(static_cast<int>(std::clamp<int64_t>(types[c], -1, 1 << 20)), {ids, size_t(n)}, c);
  }
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
  std::vector<ArrayInfo> infos;
  for (const auto& a : pointArrays_) infos.push_back({a.name, a.data.components, a.identifier});
  for (const FieldLoad& load : planFields(src_, infos, options_))
    b.addFieldStep(load.field, load.step,
                   toFloats(pointArrays_[load.array].data, load.component, options_.threads));
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
    std::vector<int64_t> ghost;
    for (const auto& a : cellArrays_)
      if (a.name == "vtkGhostType" && a.data.data) ghost = toInt64(a.data, src_, "vtkGhostType");
    if (!newLayout_) {
      addCellsOld(b, types, ghost);
    } else {
      const std::vector<int64_t> offsets = toInt64(offsets_, src_, "cell offsets");
      if (offsets.empty() || offsets[0] != 0) throw FileError(src_, "cell offsets must start at 0");
      for (size_t i = 1; i < offsets.size(); ++i)
        if (offsets[i] < offsets[i - 1])
          throw FileError(src_, "cell offsets decrease at cell ", i - 1);
      if (uint64_t(offsets.back()) != conn_.numValues())
        throw FileError(src_, "cell offsets end at ", offsets.back(), " but CONNECTIVITY has ",
                        conn_.numValues(), " ids");
      if (isFloatType(conn_.type)) throw FileError(src_, "CONNECTIVITY must hold integers");
      visitArray(conn_, [&](auto tag, auto swap) {
        using T = typename decltype(tag)::type;
        if constexpr (std::is_integral_v<T>)
          addCellsNew<T, decltype(swap)::value>(b, offsets, types, ghost);
      });
    }
  }
  if (ghostCells_)
    log::warning(src_, ": skipped ", ghostCells_, " ghost cells (vtkGhostType: owned elsewhere)");
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
