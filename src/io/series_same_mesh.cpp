#include "io/series_same_mesh.h"

#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <span>

#include "common/error.h"
#include "common/file_util.h"
#include "common/hash.h"
#include "io/readers.h"
#include "io/vtu_arrays.h"
#include "io/vtu_document.h"
#include "io_core/numeric_array.h"
#include "mesh/unstructured_mesh.h"

namespace sm::io {
namespace {

// A .vtu's points and cells, every piece in order, decoded as the reader decodes them.
void appendVtuMesh(const std::string& file, const ReadOptions& options, StepMesh& out) {
  FileBytes bytes = FileBytes::openLazily(file);
  VtuDocument doc(bytes, file, "UnstructuredGrid", options.threads, options.stopRequested);
  uint64_t points = 0, cells = 0;
  for (const VtuPiece& p : vtuPieces(doc)) {
    if (p.numPoints > 0) {
      pugi::xml_node arr = p.node.child("Points").child("DataArray");
      if (!arr) throw FileError(file, "has a piece of ", p.numPoints, " points but no <Points>");
      const std::vector<glm::dvec3> pts =
          toPoints(doc.decode(arr, p.numPoints, "points", 3), options.threads);
      out.points.insert(out.points.end(), pts.begin(), pts.end());
      points += pts.size();
    }
    if (p.numCells == 0) continue;
    const pugi::xml_node node = p.node.child("Cells");
    auto decoded = [&](const char* name, uint64_t count, const char* what) {
      const pugi::xml_node a = findDataArray(node, name);
      if (!a) throw FileError(file, "has ", p.numCells, " cells but no '", name, "' array");
      return toInt64(doc.decode(a, count, what, 1), file, what);
    };
    const std::vector<int64_t> ends = decoded("offsets", p.numCells, "cell offsets");
    const std::vector<int64_t> types = decoded("types", p.numCells, "cell types");
    const int64_t total = ends.back();
    if (total < 0) throw FileError(file, "cell offsets: the last offset is negative");
    const std::vector<int64_t> ids = decoded("connectivity", uint64_t(total), "cell connectivity");
    StepCells& c = out.cells;
    const int64_t base = int64_t(c.ids.size());
    c.types.insert(c.types.end(), types.begin(), types.end());
    for (int64_t e : ends) c.ends.push_back(base + e);
    c.ids.insert(c.ids.end(), ids.begin(), ids.end());
    cells += p.numCells;
  }
  out.pointPieces.emplace_back(file, points);
  out.cellPieces.emplace_back(file, cells);
}

// -0 and +0 are one position; every other value is compared by its bits.
glm::dvec3 canonical(glm::dvec3 p) {
  return p + glm::dvec3(0.0);
}

uint64_t digestOf(const StepMesh& s) {
  Hasher h;
  h.pod(uint64_t(s.points.size()));
  for (const glm::dvec3& p : s.points) h.pod(canonical(p));
  h.span(std::span<const int64_t>(s.cells.types));
  h.span(std::span<const int64_t>(s.cells.ends));
  h.span(std::span<const int64_t>(s.cells.ids));
  return h.digest();
}

// The files whose bytes give a step's mesh, each with its size and modification time: what
// step 0's cached digest is valid for.
uint64_t stampOf(const std::string& file, const ReadOptions& options) {
  Hasher h;
  h.str(file);
  for (int piece : options.pieces) h.pod(piece);
  std::vector<std::string> files{file};
  if (isPieceIndex(file)) {
    const std::vector<std::string> pieces = pvtuPieceFiles(file);
    files.insert(files.end(), pieces.begin(), pieces.end());
  }
  for (const std::string& f : files) {
    std::error_code ec;
    const auto time = std::filesystem::last_write_time(f, ec);
    const uintmax_t size = ec ? 0 : std::filesystem::file_size(f, ec);
    h.str(f).pod(ec ? int64_t(-1) : int64_t(time.time_since_epoch().count())).pod(size);
  }
  return h.digest();
}

// How a step's .vtu or .pvtu stores its mesh: per piece its counts and the encoded bytes of its
// points and cells (VtuDocument::encodedDigest). A writer that keeps the mesh writes the same
// bytes every step, so equal digests settle the check without decoding; 0 for other formats, or
// where an array is missing (decoding then names what is wrong).
uint64_t encodedDigestOf(const std::string& file, const ReadOptions& options) {
  std::vector<std::string> files;
  if (fileExtension(file) == ".vtu") {
    files.push_back(file);
  } else if (isPieceIndex(file)) {
    const std::vector<std::string> all = pvtuPieceFiles(file);
    for (int i : choosePieces(file, all.size(), options)) files.push_back(all[size_t(i)]);
  } else {
    return 0;
  }
  Hasher h;
  for (const std::string& f : files) {
    FileBytes bytes = FileBytes::openLazily(f);
    VtuDocument doc(bytes, f, "UnstructuredGrid", options.threads, options.stopRequested);
    for (const VtuPiece& p : vtuPieces(doc)) {
      h.pod(p.numPoints).pod(p.numCells);
      std::vector<pugi::xml_node> arrays;
      if (p.numPoints > 0) arrays.push_back(p.node.child("Points").child("DataArray"));
      if (p.numCells > 0)
        for (const char* name : {"connectivity", "offsets", "types"})
          arrays.push_back(findDataArray(p.node.child("Cells"), name));
      for (pugi::xml_node a : arrays) {
        const uint64_t d = a ? doc.encodedDigest(a) : 0;
        if (d == 0) return 0;
        h.pod(d);
      }
    }
  }
  const uint64_t d = h.digest();
  return d == 0 ? 1 : d;
}

// Step 0's digests, computed once per process for each file and pieces while they are unchanged:
// a stream checks every step against them.
struct FirstStepDigests {
  uint64_t encoded = 0, values = 0;
};
FirstStepDigests firstStepDigests(const std::string& file, const ReadOptions& options) {
  static std::mutex mutex;
  static std::map<uint64_t, FirstStepDigests> digests;  // stamp -> digests
  const uint64_t stamp = stampOf(file, options);
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (auto it = digests.find(stamp); it != digests.end()) return it->second;
  }
  const FirstStepDigests d{encodedDigestOf(file, options), digestOf(readStepMesh(file, options))};
  std::lock_guard<std::mutex> lock(mutex);
  if (digests.size() > 64) digests.clear();  // a process reads a handful of series
  digests[stamp] = d;
  return d;
}

// Item `i` of a step's points or cells, named by its piece file when the step has pieces of its
// own (a .pvtu) and by `kind` alone otherwise.
std::string itemName(const char* kind, const std::string& file,
                     const std::vector<std::pair<std::string, uint64_t>>& pieces, uint64_t i) {
  if (pieces.size() == 1 && pieces[0].first == file) return concat(kind, " ", i);
  for (const auto& [piece, count] : pieces) {
    if (i < count) return concat(kind, " ", i, " of piece '", piece, "'");
    i -= count;
  }
  return concat(kind, " ", i);
}

// Cell `i` of a step: by file order where the step was read as files, else (a mesh read whole,
// its elements type by type) as the n-th element of its type.
std::string cellName(const std::string& file, const StepMesh& s, uint64_t i) {
  if (!s.cellPieces.empty()) return itemName("cell", file, s.cellPieces, i);
  uint64_t first = i;
  while (first > 0 && s.cells.types[first - 1] == s.cells.types[i]) --first;
  const std::optional<mesh::CellType> t = mesh::fromVtkType(int(s.cells.types[i]));
  return concat(t ? mesh::cellTypeName(*t) : std::string_view("cell"), " ", i - first);
}

// "tetrahedron: points 0 1 2 3", or what the file says a cell of an unknown type is.
std::string cellText(const StepCells& c, uint64_t i) {
  const std::optional<mesh::CellType> t = mesh::fromVtkType(int(c.types[i]));
  std::string out = t ? std::string(mesh::cellTypeName(*t)) : concat("VTK type ", c.types[i]);
  out += ": points";
  const int64_t begin = i == 0 ? 0 : c.ends[i - 1];
  for (int64_t j = begin; j < c.ends[i] && j < int64_t(c.ids.size()); ++j)
    out += concat(" ", c.ids[size_t(j)]);
  return out;
}

[[noreturn]] void throwMoved(const std::string& path, uint64_t k, const SeriesStep& step,
                             const std::string& where, const glm::dvec3& first,
                             const glm::dvec3& later) {
  auto xyz = [](const glm::dvec3& p) { return concat("(", p.x, ", ", p.y, ", ", p.z, ")"); };
  throw FileError(path, "step ", k, " ('", step.file, "') has ", where, " at ", xyz(later),
                  ", step 0 at ", xyz(first),
                  ": every step of a series must be the same mesh, its points in the same places "
                  "and order (render the files of a moving or renumbered mesh one at a time)");
}

}  // namespace

StepMesh readStepMesh(const std::string& file, const ReadOptions& options) {
  if (fileExtension(file) == ".vtu") {
    StepMesh out;
    appendVtuMesh(file, options, out);
    return out;
  }
  if (isPieceIndex(file)) {
    StepMesh out;
    const std::vector<std::string> files = pvtuPieceFiles(file);
    for (int i : choosePieces(file, files.size(), options))
      appendVtuMesh(files[size_t(i)], options, out);
    return out;
  }
  ReadOptions o = options;
  o.loadFields = false;
  o.fields.clear();
  o.step.reset();
  return stepMeshOf(readMesh(file, o));
}

StepMesh stepMeshOf(const mesh::UnstructuredMesh& m) {
  StepMesh out;
  out.points = m.points;
  StepCells& c = out.cells;
  c.types.reserve(m.numCells());
  c.ends.reserve(m.numCells());
  for (mesh::CellType t : mesh::kAllCellTypes) {
    const std::vector<uint32_t>& ids = m.cells[mesh::typeIndex(t)];
    const int vtk = mesh::toVtkType(t);
    for (size_t i = 0; i < ids.size(); i += mesh::numVerts(t)) {
      c.types.push_back(vtk);
      c.ids.insert(c.ids.end(), ids.begin() + ptrdiff_t(i),
                   ids.begin() + ptrdiff_t(i + mesh::numVerts(t)));
      c.ends.push_back(int64_t(c.ids.size()));
    }
  }
  out.pointPieces.emplace_back(m.source, m.points.size());
  return out;
}

std::optional<uint64_t> firstMovedPoint(const std::vector<glm::dvec3>& first,
                                        const std::vector<glm::dvec3>& later) {
  const size_t n = std::min(first.size(), later.size());
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec3 a = canonical(first[i]), b = canonical(later[i]);
    if (std::memcmp(&a, &b, sizeof a) != 0) return i;  // by bits, as digestOf hashes them
  }
  if (first.size() != later.size()) return n;
  return std::nullopt;
}

std::optional<uint64_t> firstChangedCell(const StepCells& first, const StepCells& later) {
  const size_t n = std::min(first.types.size(), later.types.size());
  for (size_t i = 0; i < n; ++i) {
    const int64_t a = i == 0 ? 0 : first.ends[i - 1], b = i == 0 ? 0 : later.ends[i - 1];
    const auto bad = [](const StepCells& c, int64_t begin, size_t j) {
      return begin < 0 || c.ends[j] < begin || c.ends[j] > int64_t(c.ids.size());
    };
    if (bad(first, a, i) || bad(later, b, i)) return i;  // offsets the reader would refuse
    if (first.types[i] != later.types[i] || first.ends[i] - a != later.ends[i] - b ||
        !std::equal(first.ids.begin() + a, first.ids.begin() + first.ends[i],
                    later.ids.begin() + b))
      return i;
  }
  if (first.types.size() != later.types.size()) return n;
  return std::nullopt;
}

void checkSameMesh(const std::string& path, uint64_t k, const SeriesStep& step,
                   const StepMesh& first, const StepMesh& later) {
  if (first.points.size() != later.points.size() ||
      first.cells.types.size() != later.cells.types.size())
    throw FileError(path, "step ", k, " ('", step.file, "') has ", later.points.size(),
                    " points and ", later.cells.types.size(), " cells, step 0 ",
                    first.points.size(), " and ", first.cells.types.size(),
                    ": every step of a series must be the same mesh");
  if (const std::optional<uint64_t> i = firstMovedPoint(first.points, later.points))
    throwMoved(path, k, step, itemName("point", step.file, later.pointPieces, *i), first.points[*i],
               later.points[*i]);
  if (const std::optional<uint64_t> i = firstChangedCell(first.cells, later.cells))
    throw FileError(path, "step ", k, " ('", step.file, "') has ", cellName(step.file, later, *i),
                    " (", cellText(later.cells, *i), "), step 0 (", cellText(first.cells, *i),
                    "): every step of a series must be the same mesh, its cells joining the same "
                    "points in the same order (render the files of a remeshed or renumbered mesh "
                    "one at a time)");
}

void checkSameMesh(const std::string& path, const std::vector<SeriesStep>& steps, uint64_t k,
                   const ReadOptions& options) {
  if (k == 0) return;
  const FirstStepDigests first = firstStepDigests(steps[0].file, options);
  if (first.encoded != 0 && encodedDigestOf(steps[k].file, options) == first.encoded) return;
  checkSameMesh(path, steps, k, options, readStepMesh(steps[k].file, options));
}

void checkSameMesh(const std::string& path, const std::vector<SeriesStep>& steps, uint64_t k,
                   const ReadOptions& options, const StepMesh& later) {
  if (k == 0 || digestOf(later) == firstStepDigests(steps[0].file, options).values) return;
  // Step 0's files may have been replaced after its digest was taken: then this finds no change.
  checkSameMesh(path, k, steps[k], readStepMesh(steps[0].file, options), later);
}

}  // namespace sm::io
