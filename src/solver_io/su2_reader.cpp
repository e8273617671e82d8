// SU2 native meshes (docs/FORMATS.md): "KEY= value" lines, % comments. NDIME= 3; NELEM= n then n
// lines "VTKTYPE id... [index]"; NPOIN= n [ndomain] then n lines "x y z [index]"; NMARK= with
// MARKER_TAG= / MARKER_ELEMS= n boundary lists (skipped); NZONE= / IZONE= k for several zones,
// each a piece. Element types are VTK's codes with VTK's vertex order and 0-based point ids.
#include <algorithm>
#include <cstring>

#include "common/error.h"
#include "io_core/text_scan.h"
#include "io_core/weld.h"
#include "mesh/mesh_builder.h"
#include "solver_io/pieced_readers.h"

namespace sm::io {
namespace {

// Point ids an element of this VTK type lists; 0 for a type SU2 does not have.
uint32_t idsOf(int64_t vtkType) {
  switch (vtkType) {
    case 3:
      return 2;
    case 5:
      return 3;
    case 9:
      return 4;
    case 10:
      return 4;
    case 12:
      return 8;
    case 13:
      return 6;
    case 14:
      return 5;
    default:
      return 0;
  }
}

struct Zone {
  uint64_t elements = 0;
  std::vector<uint8_t> types;  // full reads
  std::vector<int64_t> ids;
  std::vector<glm::dvec3> points;
};

class Su2Parser {
 public:
  Su2Parser(const FileBytes& bytes, const std::string& src, const ReadOptions* options)
      : pos_(reinterpret_cast<const char*>(bytes.data())),
        end_(pos_ + bytes.size()),
        src_(src),
        options_(options) {}

  // Every zone's element count; with `wanted`, the elements and points of those zones too.
  std::vector<Zone> parse(const std::vector<int>& wanted = {}) {
    std::vector<Zone> zones(1);
    int zone = 0;
    uint64_t declared = 1;  // NZONE=
    for (std::string_view line; next(line);) {
      std::string_view key, value;
      if (!keyword(line, key, value))
        fail("expected a keyword such as NELEM= or NPOIN=, found '", printable(line), "'");
      if (key == "NZONE") {
        declared = number(value, "NZONE");
        if (declared < 1 || zones.size() > 1 || zones[0].elements)
          fail("NZONE= ", declared, " is not a zone count that can come here");
      } else if (key == "IZONE") {
        // Zones come in order, so that the zones allocated are the zones the file holds.
        const uint64_t k = number(value, "IZONE");
        if (k < 1 || k > declared || k > zones.size() + 1)
          fail("IZONE= ", k, " after ", zones.size(), " zone(s) of the ", declared,
               " NZONE= declares");
        if (k > zones.size()) zones.emplace_back();
        zone = int(k - 1);
      } else if (key == "NDIME") {
        const uint64_t d = number(value, "NDIME");
        if (d != 3) fail("NDIME= ", d, ": only 3D meshes (NDIME= 3) are read");
      } else if (key == "NELEM") {
        if (options_) throwIfStopped(options_->stopRequested, src_);
        zones[zone].elements = number(value, "NELEM");
        elements(zones[zone], isWanted(wanted, zone));
      } else if (key == "NPOIN") {
        if (options_) throwIfStopped(options_->stopRequested, src_);
        points(zones[zone], number(firstToken(value), "NPOIN"), isWanted(wanted, zone));
      } else if (key == "MARKER_ELEMS") {
        skip(number(value, "MARKER_ELEMS"), "MARKER_ELEMS");
      }  // NMARK, MARKER_TAG and other keywords have no lines of their own
    }
    if (zones.size() != declared)
      fail("the file ends after ", zones.size(), " of the ", declared, " zones NZONE= declares");
    return zones;
  }

 private:
  static bool isWanted(const std::vector<int>& wanted, int zone) {
    return std::find(wanted.begin(), wanted.end(), zone) != wanted.end();
  }

  // The next line that is not blank or a % comment, without its end-of-line blanks.
  bool next(std::string_view& line) {
    while (pos_ < end_) {
      const char* b = pos_;
      const char* e = static_cast<const char*>(std::memchr(pos_, '\n', size_t(end_ - pos_)));
      if (!e) e = end_;
      pos_ = e < end_ ? e + 1 : e;
      ++line_;
      while (b < e && isSpace(*b)) ++b;
      while (e > b && isSpace(e[-1])) --e;
      if (b == e || *b == '%') continue;
      line = {b, size_t(e - b)};
      return true;
    }
    return false;
  }
  bool dataLine(std::string_view& line, uint64_t i, uint64_t n, const char* what) {
    if (!next(line)) fail("the file ends after ", i, " of the ", n, " lines of ", what);
    if (line.find('=') != std::string_view::npos)
      fail("'", printable(line), "' after ", i, " of the ", n, " lines ", what, " declares");
    return true;
  }
  static bool keyword(std::string_view line, std::string_view& key, std::string_view& value) {
    const size_t eq = line.find('=');
    if (eq == std::string_view::npos) return false;
    key = line.substr(0, eq);
    while (!key.empty() && isSpace(key.back())) key.remove_suffix(1);
    value = line.substr(eq + 1);
    return !key.empty();
  }
  static std::string_view firstToken(std::string_view v) { return TextCursor(v).token(); }
  uint64_t number(std::string_view value, const char* key) const {
    TextCursor c(value);
    uint64_t n = 0;
    std::string_view tok = c.token();
    if (!parseNumber(tok, n) || !c.atEnd()) fail(key, "= '", printable(value), "' is not a count");
    return n;
  }
  uint64_t remaining() const { return uint64_t(end_ - pos_); }
  void checkLines(uint64_t n, const char* what) const {
    if (n > remaining() / 2 + 1)
      fail(what, "= ", n, " declares more lines than the ", remaining(), " bytes left can hold");
  }

  void elements(Zone& z, bool keep) {
    checkLines(z.elements, "NELEM");
    if (!keep) return skip(z.elements, "NELEM");
    z.types.reserve(z.elements);
    int64_t v[10];
    for (uint64_t e = 0; e < z.elements; ++e) {
      std::string_view line;
      dataLine(line, e, z.elements, "elements NELEM=");
      TextCursor c(line);
      uint32_t n = 0;
      for (std::string_view tok = c.token(); !tok.empty(); tok = c.token()) {
        if (n == 10 || !parseNumber(tok, v[n]))
          fail("element ", e, ": '", printable(tok), "' is not a point id");
        ++n;
      }
      const uint32_t ids = idsOf(v[0]);
      if (ids == 0) fail("element ", e, " has type ", v[0], ", not an SU2 element type");
      if (n != ids + 1 && n != ids + 2)
        fail("element ", e, " of type ", v[0], " has ", n - 1, " numbers, not ", ids,
             " point ids (and an optional index)");
      z.types.push_back(uint8_t(v[0]));
      z.ids.insert(z.ids.end(), v + 1, v + 1 + ids);
    }
  }

  void points(Zone& z, uint64_t n, bool keep) {
    checkLines(n, "NPOIN");
    if (!keep) return skip(n, "NPOIN");
    z.points.resize(n);
    for (uint64_t i = 0; i < n; ++i) {
      std::string_view line;
      dataLine(line, i, n, "points NPOIN=");
      TextCursor c(line);
      double x[4];
      uint32_t k = 0;
      for (std::string_view tok = c.token(); !tok.empty(); tok = c.token()) {
        if (k == 4 || !parseNumber(tok, x[k]))
          fail("point ", i, ": '", printable(tok), "' is not a coordinate");
        ++k;
      }
      if (k != 3 && k != 4) fail("point ", i, " has ", k, " numbers, not x y z (and an index)");
      z.points[i] = {x[0], x[1], x[2]};
    }
  }

  void skip(uint64_t n, const char* what) {
    checkLines(n, what);
    std::string_view line;
    for (uint64_t i = 0; i < n; ++i) dataLine(line, i, n, what);
  }

  template <typename... Args>
  [[noreturn]] void fail(Args&&... args) const {
    throw FileError(src_, "line ", line_, ": ", std::forward<Args>(args)...);
  }

  const char* pos_;
  const char* end_;
  const std::string& src_;
  const ReadOptions* options_;
  uint64_t line_ = 0;
};

std::string pieceName(const std::string& src, size_t zones, size_t z) {
  return zones > 1 ? concat(src, ", zone ", z + 1) : src;
}

mesh::UnstructuredMesh buildZone(Zone& z, const std::string& src, int piece,
                                 const ReadOptions& options) {
  mesh::MeshBuilder b(src);
  b.setPoints(std::move(z.points));
  const uint64_t n = z.types.size();
  if (options.cellOrigins)
    b.keepCellOrigins(n);
  else
    b.setFileCells(n);
  uint64_t perType[15] = {};
  for (uint8_t t : z.types) ++perType[t];
  b.reserveCells(mesh::CellType::Tet, perType[10]);
  b.reserveCells(mesh::CellType::Hex, perType[12]);
  b.reserveCells(mesh::CellType::Wedge, perType[13]);
  b.reserveCells(mesh::CellType::Pyramid, perType[14]);
  const int64_t* ids = z.ids.data();
  for (uint64_t e = 0; e < n; ++e) {
    const uint32_t k = idsOf(z.types[e]);
    b.addVtkCell(z.types[e], {ids, k}, e, piece);
    ids += k;
  }
  return b.finish();
}

}  // namespace

PiecedLayout su2Layout(const FileBytes& bytes, const std::string& source) {
  const std::vector<Zone> zones = Su2Parser(bytes, source, nullptr).parse();
  PiecedLayout l;
  for (size_t z = 0; z < zones.size(); ++z) {
    l.pieces.push_back(pieceName(source, zones.size(), z));
    l.pieceCells.push_back(zones[z].elements);
  }
  l.files = {source};
  return l;
}

mesh::UnstructuredMesh readSu2(const FileBytes& bytes, const std::string& source,
                               const ReadOptions& options) {
  const PiecedLayout layout = su2Layout(bytes, source);
  const std::vector<int> pieces = choosePieces(source, layout.pieces.size(), options);
  // SU2 files hold no fields: a named one is an error listing none.
  piecedFieldSteps(source, layout, options);
  std::vector<Zone> zones = Su2Parser(bytes, source, &options).parse(pieces);
  std::vector<mesh::UnstructuredMesh> meshes;
  for (int p : pieces) {
    throwIfStopped(options.stopRequested, source);
    meshes.push_back(buildZone(zones[p], source, p, options));
  }
  // One piece needs no weld (which would copy it).
  mesh::UnstructuredMesh m =
      meshes.size() == 1 ? std::move(meshes[0]) : weldPieces(source, std::move(meshes));
  return m;
}

}  // namespace sm::io
