// Gmsh .msh 4.1 sections (gmsh.info/doc/texinfo/gmsh.html#MSH-file-format). In binary files the
// bodies of $Entities, $PartitionedEntities, $Nodes and $Elements are binary (ints of 4 bytes,
// size_t of 8, doubles), while $MeshFormat and the headers of $NodeData and $ElementData stay
// text; their entries are binary (an int tag and the doubles). Every count is checked against the
// bytes left before anything is allocated, since these readers are fuzzed.
#include "solver_io/gmsh_sections.h"

#include <algorithm>
#include <cstring>

#include "common/error.h"
#include "io_core/numeric_array.h"
#include "io_core/text_scan.h"

namespace sm::io {

namespace {

// {dimension, nodes, corners} of gmsh's types 1 to 140, as gmsh 4.8's getElementProperties gives
// them (the unit tests compare); {-1, 0, 0} for numbers gmsh does not use.
constexpr int kTypes[140][3] = {
    {1, 2, 2},   {2, 3, 3},   {2, 4, 4},   {3, 4, 4},   {3, 8, 8},   {3, 6, 6},   {3, 5, 5},
    {1, 3, 2},   {2, 6, 3},   {2, 9, 4},   {3, 10, 4},  {3, 27, 8},  {3, 18, 6},  {3, 14, 5},
    {0, 1, 1},   {2, 8, 4},   {3, 20, 8},  {3, 15, 6},  {3, 13, 5},  {2, 9, 3},   {2, 10, 3},
    {2, 12, 3},  {2, 15, 3},  {2, 15, 3},  {2, 21, 3},  {1, 4, 2},   {1, 5, 2},   {1, 6, 2},
    {3, 20, 4},  {3, 35, 4},  {3, 56, 4},  {3, 22, 4},  {3, 28, 4},  {2, 0, 0},   {3, 0, 0},
    {2, 16, 4},  {2, 25, 4},  {2, 36, 4},  {2, 12, 4},  {2, 16, 4},  {2, 20, 4},  {2, 28, 3},
    {2, 36, 3},  {2, 45, 3},  {2, 55, 3},  {2, 66, 3},  {2, 49, 4},  {2, 64, 4},  {2, 81, 4},
    {2, 100, 4}, {2, 121, 4}, {2, 18, 3},  {2, 21, 3},  {2, 24, 3},  {2, 27, 3},  {2, 30, 3},
    {2, 24, 4},  {2, 28, 4},  {2, 32, 4},  {2, 36, 4},  {2, 40, 4},  {1, 7, 2},   {1, 8, 2},
    {1, 9, 2},   {1, 10, 2},  {1, 11, 2},  {-1, 0, 0},  {-1, 0, 0},  {2, 0, 0},   {-1, 0, 0},
    {3, 84, 4},  {3, 120, 4}, {3, 165, 4}, {3, 220, 4}, {3, 286, 4}, {-1, 0, 0},  {-1, 0, 0},
    {-1, 0, 0},  {3, 34, 4},  {3, 40, 4},  {3, 46, 4},  {3, 52, 4},  {3, 58, 4},  {1, 1, 2},
    {2, 1, 3},   {2, 1, 4},   {3, 1, 4},   {3, 1, 8},   {3, 1, 6},   {-1, 0, 0},  {-1, 0, 0},
    {3, 64, 8},  {3, 125, 8}, {3, 216, 8}, {3, 343, 8}, {3, 512, 8}, {3, 729, 8}, {3, 1000, 8},
    {3, 32, 8},  {3, 44, 8},  {3, 56, 8},  {3, 68, 8},  {3, 80, 8},  {3, 92, 8},  {3, 104, 8},
    {-1, 0, 0},  {-1, 0, 0},  {-1, 0, 0},  {-1, 0, 0},  {-1, 0, 0},  {-1, 0, 0},  {-1, 0, 0},
    {-1, 0, 0},  {-1, 0, 0},  {-1, 0, 0},  {-1, 0, 0},  {-1, 0, 0},  {3, 30, 5},  {3, 55, 5},
    {3, 91, 5},  {3, 140, 5}, {3, 204, 5}, {3, 285, 5}, {3, 385, 5}, {3, 21, 5},  {3, 29, 5},
    {3, 37, 5},  {3, 45, 5},  {3, 53, 5},  {3, 61, 5},  {3, 69, 5},  {3, 1, 5},   {0, 0, 0},
    {1, 0, 0},   {2, 0, 0},   {3, 0, 0},   {3, 16, 4},  {-1, 0, 0},  {-1, 0, 0},  {-1, 0, 0}};

int linearVtkType(int dim, uint32_t corners) {
  switch (dim * 16 + int(corners)) {
    case 3 * 16 + 4:
      return 10;
    case 3 * 16 + 8:
      return 12;
    case 3 * 16 + 6:
      return 13;
    case 3 * 16 + 5:
      return 14;
    case 2 * 16 + 3:
      return 5;
    case 2 * 16 + 4:
      return 9;
    case 1 * 16 + 2:
      return 3;
    case 0 * 16 + 1:
      return 1;
    default:
      return -1;
  }
}

}  // namespace

GmshElementType gmshElementType(int type) {
  if (type < 1 || type > 140) return {};
  const int* t = kTypes[type - 1];
  // Polygons and polyhedra (no fixed node count) and order-0 elements (fewer nodes than corners)
  // have no VTK counterpart here.
  if (t[0] < 0 || t[1] == 0 || t[1] < t[2]) return {};
  const int vtk = linearVtkType(t[0], uint32_t(t[2]));
  if (vtk < 0) return {};
  return {t[0], uint32_t(t[1]), uint32_t(t[2]), vtk};
}

class GmshParser::Cursor {
 public:
  Cursor(const char* begin, const char* end, const std::string& src)
      : begin_(begin), end_(end), pos(begin), src_(src) {}

  template <typename... Args>
  [[noreturn]] void fail(const char* at, Args&&... args) const {
    if (binary)
      throw FileError(src_, "section $", section, ", byte ", at - begin_, ": ",
                      std::forward<Args>(args)...);
    throw FileError(src_, "line ", 1 + std::count(begin_, at, '\n'), ": ",
                    std::forward<Args>(args)...);
  }
  uint64_t remaining() const { return uint64_t(end_ - pos); }
  const char* end() const { return end_; }

  std::string_view token() {
    TextCursor t(pos, end_);
    std::string_view tok = t.token();
    pos = t.pos();
    return tok;
  }
  // The rest of the line, without surrounding blanks; moves past its newline.
  std::string_view line() {
    while (pos < end_ && (*pos == ' ' || *pos == '\t' || *pos == '\r')) ++pos;
    const char* b = pos;
    if (pos >= end_) return {};
    const char* e = static_cast<const char*>(std::memchr(pos, '\n', remaining()));
    if (!e) e = end_;
    pos = e < end_ ? e + 1 : e;
    while (e > b && isSpace(e[-1])) --e;
    return {b, size_t(e - b)};
  }
  void skipSpace() {
    while (pos < end_ && isSpace(*pos)) ++pos;
  }

  template <class T>
  T raw(const char* what) {
    if (remaining() < sizeof(T)) fail(pos, "the file ends in ", what);
    T v = loadAs<T>(reinterpret_cast<const uint8_t*>(pos), swap);
    pos += sizeof(T);
    return v;
  }
  template <class T>
  T text(const char* what) {
    const char* at = pos;
    std::string_view tok = token();
    T v{};
    if (tok.empty()) fail(at, "the file ends in ", what);
    if (!parseNumber(tok, v)) fail(at, what, " is '", printable(tok), "', not a number");
    return v;
  }
  uint64_t size(const char* what) { return binary ? raw<uint64_t>(what) : text<uint64_t>(what); }
  int integer(const char* what) {
    if (binary) return raw<int32_t>(what);
    const char* at = pos;
    int64_t v = text<int64_t>(what);
    if (v < INT32_MIN || v > INT32_MAX) fail(at, what, " ", v, " is out of range");
    return int(v);
  }
  double real(const char* what) { return binary ? raw<double>(what) : text<double>(what); }
  // A count of items of at least `bytesEach` bytes (binary) or 2 characters per number (text).
  uint64_t count(const char* what, uint64_t bytesEach, uint64_t numbersEach) {
    const char* at = pos;
    uint64_t n = size(what);
    const uint64_t most = binary
                              ? remaining() / std::max<uint64_t>(bytesEach, 1)
                              : maxNumbersInText(remaining()) / std::max<uint64_t>(numbersEach, 1);
    if (n > most)
      fail(at, what, " is ", n, ", more than the ", remaining(), " bytes left can hold");
    return n;
  }

  bool binary = false;
  bool swap = false;
  std::string section;

 private:
  const char* begin_;
  const char* end_;

 public:
  const char* pos;

 private:
  const std::string& src_;
};

GmshParser::GmshParser(const FileBytes& bytes, const std::string& source, bool full,
                       const StopRequested& stop)
    : begin_(reinterpret_cast<const char*>(bytes.data())),
      end_(begin_ + bytes.size()),
      src_(source),
      full_(full),
      stop_(stop) {}

GmshFile GmshParser::parse() {
  Cursor c(begin_, end_, src_);
  for (c.skipSpace(); c.pos < c.end(); c.skipSpace()) {
    throwIfStopped(stop_, src_);
    const char* at = c.pos;
    c.binary = false;
    std::string_view head = c.line();
    if (head.empty() || head[0] != '$')
      c.fail(at, "expected a section such as $Nodes, found '", printable(head), "'");
    const std::string name(head.substr(1));
    c.section = name;
    if (!haveFormat_ && name != "MeshFormat")
      c.fail(at, "the file does not start with $MeshFormat: not a Gmsh .msh file");
    c.binary = file_.binary;
    c.swap = file_.swap;
    if (name == "MeshFormat") {
      c.binary = false;
      meshFormat(c);
    } else if (name == "PartitionedEntities") {
      partitionedEntities(c);
    } else if (name == "Nodes" && !haveNodes_) {
      nodesSection(c);
    } else if (name == "Elements" && !haveElements_) {
      elementsSection(c);
    } else if (name == "NodeData" || name == "ElementData") {
      dataSection(c, name == "ElementData");
    } else {  // $PhysicalNames, $Entities, $ElementNodeData, repeated meshes, unknown sections
      skipSection(c, name);
    }
    c.binary = false;
    expectEnd(c, name);
  }
  if (!haveFormat_) throw FileError(src_, "is empty: not a Gmsh .msh file");
  if (!haveNodes_) throw FileError(src_, "has no $Nodes section");
  if (!haveElements_) throw FileError(src_, "has no $Elements section");
  return std::move(file_);
}

void GmshParser::meshFormat(Cursor& c) {
  const char* at = c.pos;
  std::string_view version = c.token();
  if (version != "4.1") {
    if (!version.empty() && version[0] == '2')
      c.fail(at, "a .msh ", printable(version),
             " file; only version 4.1 is read (save it again "
             "with gmsh -save -format msh41)");
    c.fail(at, "version '", printable(version), "'; only .msh 4.1 is read");
  }
  const int type = c.integer("the file type");
  const int dataSize = c.integer("the data size");
  if (type != 0 && type != 1)
    c.fail(at, "file type ", type, " is neither 0 (ASCII) nor 1 (binary)");
  if (dataSize != 8) c.fail(at, "data size ", dataSize, "; only 8 (64-bit size_t) is read");
  c.line();
  if (type == 1) {
    const char* one = c.pos;
    const uint32_t marker = c.raw<uint32_t>("the endianness marker");
    if (marker != 1 && marker != 0x01000000u)
      c.fail(one, "the binary endianness marker is ", marker, ", not 1");
    file_.binary = true;
    file_.swap = marker != 1;
  }
  haveFormat_ = true;
}

void GmshParser::partitionedEntities(Cursor& c) {
  const char* at = c.pos;
  const uint64_t n = c.size("the partition count");
  if (n < 1 || n > c.remaining() || n > INT32_MAX)
    c.fail(at, "the partition count ", n, " is wrong");
  file_.partitions = int(n);
  const uint64_t ghosts = c.count("the ghost entity count", 8, 2);
  for (uint64_t i = 0; i < ghosts; ++i) {
    ghosts_.push_back(c.integer("a ghost entity tag"));
    c.integer("a ghost entity's partition");
  }
  uint64_t counts[4];
  for (uint64_t& k : counts) k = c.count("an entity count", 20, 5);
  for (int dim = 0; dim < 4; ++dim)
    for (uint64_t i = 0; i < counts[dim]; ++i) entity(c, dim);
}

void GmshParser::entity(Cursor& c, int dim) {
  const int tag = c.integer("an entity tag");
  c.integer("a parent entity's dimension");
  c.integer("a parent entity's tag");
  const uint64_t parts = c.count("an entity's partition count", 4, 1);
  for (uint64_t k = 0; k < parts; ++k) {
    const char* at = c.pos;
    const int p = c.integer("a partition");
    if (p < 1 || p > file_.partitions)
      c.fail(at, "entity ", tag, " is in partition ", p, " of ", file_.partitions);
    if (k == 0) entityPartition_[{dim, tag}] = p;
  }
  for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) c.real("an entity's bounds");
  const uint64_t physicals = c.count("a physical tag count", 4, 1);
  for (uint64_t k = 0; k < physicals; ++k) c.integer("a physical tag");
  if (dim == 0) return;
  const uint64_t bounding = c.count("a bounding entity count", 4, 1);
  for (uint64_t k = 0; k < bounding; ++k) c.integer("a bounding entity");
}

void GmshParser::nodesSection(Cursor& c) {
  const uint64_t blocks = c.count("the node block count", 20, 4);
  uint64_t left = c.count("the node count", 32, 4);
  c.size("the smallest node tag");
  c.size("the largest node tag");
  if (!full_ && !c.binary) {  // the layout needs no node: jump to the end
    skipSection(c, "Nodes");
    haveNodes_ = true;
    return;
  }
  if (full_) {
    file_.nodeTags.reserve(left);
    file_.nodes.reserve(left);
  }
  for (uint64_t b = 0; b < blocks; ++b) {
    throwIfStopped(stop_, src_);
    nodeBlock(c, left);
  }
  if (left != 0) c.fail(c.pos, "the nodes' header declares ", left, " more nodes than its blocks");
  haveNodes_ = true;
}

void GmshParser::nodeBlock(Cursor& c, uint64_t& left) {
  const char* at = c.pos;
  const int dim = c.integer("a node block's dimension");
  c.integer("a node block's entity");
  const int parametric = c.integer("a node block's parametric flag");
  if (dim < 0 || dim > 3 || parametric < 0 || parametric > 1)
    c.fail(at, "a node block has dimension ", dim, " and parametric flag ", parametric);
  const uint64_t values = 3 + (parametric ? dim : 0);
  const uint64_t n = c.count("a node block's node count", 8 + 8 * values, 1 + values);
  if (n > left) c.fail(at, "the node blocks hold more nodes than the header's ", left);
  left -= n;
  if (!full_) {  // binary layout read: jump over
    c.pos += n * 8 * (1 + values);
    return;
  }
  for (uint64_t i = 0; i < n; ++i) file_.nodeTags.push_back(c.size("a node tag"));
  for (uint64_t i = 0; i < n; ++i) {
    double v[6];
    for (uint64_t k = 0; k < values; ++k) v[k] = c.real("a node coordinate");
    file_.nodes.push_back({v[0], v[1], v[2]});
  }
}

void GmshParser::elementsSection(Cursor& c) {
  const uint64_t blocks = c.count("the element block count", 20, 4);
  uint64_t left = c.count("the element count", 16, 2);
  c.size("the smallest element tag");
  c.size("the largest element tag");
  for (uint64_t b = 0; b < blocks; ++b) {
    throwIfStopped(stop_, src_);
    elementBlock(c, left);
  }
  if (left != 0)
    c.fail(c.pos, "the elements' header declares ", left, " more elements than its blocks");
  haveElements_ = true;
}

void GmshParser::elementBlock(Cursor& c, uint64_t& left) {
  GmshElementBlock b;
  c.skipSpace();
  b.where = c.pos;
  b.dim = c.integer("an element block's dimension");
  b.entity = c.integer("an element block's entity");
  b.type = c.integer("an element block's type");
  const GmshElementType t = gmshElementType(b.type);
  if (t.dim < 0) c.fail(b.where, "element type ", b.type, " is not one this reader knows");
  if (t.dim != b.dim)
    c.fail(b.where, "element type ", b.type, " is ", t.dim, "D in a block of dimension ", b.dim);
  b.count = c.count("an element block's element count", 8 * (1 + t.nodes), 1 + t.nodes);
  if (b.count > left) c.fail(b.where, "the element blocks hold more than the header's ", left);
  left -= b.count;
  b.piece = pieceOf(b.dim, b.entity);
  if (b.piece < 0) {
    c.fail(b.where, "the elements of entity ", b.entity, " (dimension ", b.dim,
           ") are in no partition");
  }
  if (!full_) {
    if (c.binary)
      c.pos += b.count * 8 * (1 + t.nodes);
    else
      skipLines(c, b.count + 1);  // the rest of the header's line, then one line per element
  } else {
    b.tags.reserve(b.count);
    if (t.dim == 3) b.corners.reserve(b.count * t.corners);
    for (uint64_t e = 0; e < b.count; ++e) {
      if (!c.binary && t.dim == 3) {
        c.skipSpace();
        b.lines.push_back(c.pos);
      }
      b.tags.push_back(c.size("an element tag"));
      for (uint32_t k = 0; k < t.nodes; ++k) {
        const uint64_t node = c.size("an element's node");
        if (t.dim == 3 && k < t.corners) b.corners.push_back(node);
      }
    }
  }
  if (std::find(ghosts_.begin(), ghosts_.end(), b.entity) != ghosts_.end() && b.dim == 3) return;
  file_.blocks.push_back(std::move(b));
}

int GmshParser::pieceOf(int dim, int entity) const {
  if (file_.partitions == 0) return 0;
  const auto it = entityPartition_.find({dim, entity});
  return it == entityPartition_.end() ? -1 : it->second - 1;
}

void GmshParser::dataSection(Cursor& c, bool cells) {
  GmshDataSection s;
  s.cells = cells;
  const char* at = c.pos;
  const int64_t strings = c.text<int64_t>("the string tag count");
  if (strings < 0 || uint64_t(strings) > c.remaining()) c.fail(at, "bad string tag count");
  c.line();
  for (int64_t i = 0; i < strings; ++i) {
    std::string_view tag = c.line();
    if (tag.size() >= 2 && tag.front() == '"' && tag.back() == '"')
      tag = tag.substr(1, tag.size() - 2);
    if (i == 0) s.name = tag;
  }
  if (s.name.empty()) c.fail(at, "a data section has no name (string tag)");
  const int64_t reals = c.text<int64_t>("the real tag count");
  if (reals < 0 || uint64_t(reals) > c.remaining()) c.fail(at, "bad real tag count");
  for (int64_t i = 0; i < reals; ++i) {
    const double v = c.text<double>("a real tag");
    if (i == 0) s.time = v;
  }
  at = c.pos;
  const int64_t ints = c.text<int64_t>("the integer tag count");
  if (ints < 3 || uint64_t(ints) > c.remaining())
    c.fail(at, "a data section has ", ints,
           " integer tags, fewer than the 3 (step, components, "
           "count) it needs");
  int64_t tags[3] = {0, 0, 0};
  for (int64_t i = 0; i < ints; ++i) {
    const int64_t v = c.text<int64_t>("an integer tag");
    if (i < 3) tags[i] = v;
  }
  s.step = tags[0];
  if (tags[1] < 1 || tags[1] > 9) c.fail(at, "a data section has ", tags[1], " components");
  s.components = uint32_t(tags[1]);
  const uint64_t each = file_.binary ? 4 + 8 * s.components : 2 * (1 + s.components);
  if (file_.binary) c.line();
  if (tags[2] < 0 || uint64_t(tags[2]) > c.remaining() / each)
    c.fail(at, "a data section declares ", tags[2], " values, more than the file holds");
  s.count = uint64_t(tags[2]);
  if (file_.binary) {
    s.values = c.pos;
    c.pos += s.count * each;
  } else {
    s.values = c.pos;
    skipLines(c, s.count + 1);
  }
  file_.data.push_back(std::move(s));
}

void GmshParser::forEachValue(
    const GmshDataSection& s,
    const std::function<void(int64_t, std::span<const double>)>& visit) const {
  Cursor c(begin_, end_, src_);
  c.binary = file_.binary;
  c.swap = file_.swap;
  c.section = s.cells ? "ElementData" : "NodeData";
  c.pos = s.values;
  double v[9];
  for (uint64_t i = 0; i < s.count; ++i) {
    const int64_t tag = c.binary ? c.raw<int32_t>("a data tag") : c.text<int64_t>("a data tag");
    for (uint32_t k = 0; k < s.components; ++k) v[k] = c.real("a data value");
    visit(tag, {v, s.components});
  }
}

void GmshParser::skipLines(Cursor& c, uint64_t n) const {
  for (uint64_t i = 0; i < n && c.pos < c.end(); ++i) c.line();
}

void GmshParser::skipSection(Cursor& c, const std::string& name) {
  const std::string endTag = "$End" + name;
  std::string_view rest(c.pos, c.remaining());
  for (size_t at = rest.find(endTag); at != std::string_view::npos;
       at = rest.find(endTag, at + 1)) {
    const bool lineStart = at == 0 || rest[at - 1] == '\n';
    const size_t after = at + endTag.size();
    if (lineStart && (after == rest.size() || isSpace(rest[after]))) {
      c.pos += at;
      return;
    }
  }
  c.fail(c.pos, "section $", name, " has no ", endTag);
}

void GmshParser::expectEnd(Cursor& c, const std::string& name) {
  c.skipSpace();
  const char* at = c.pos;
  std::string_view tok = c.token();
  if (tok != "$End" + name)
    c.fail(at, "expected $End", name, ", found '", printable(tok),
           "' (the section holds more or fewer values than it declares)");
}

}  // namespace sm::io
