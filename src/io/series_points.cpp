#include "io/series_points.h"

#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>

#include "common/error.h"
#include "common/file_util.h"
#include "common/hash.h"
#include "io/numeric_array.h"
#include "io/readers.h"
#include "io/vtu_arrays.h"
#include "io/vtu_document.h"

namespace sm::io {
namespace {

// A .vtu's points, every piece in order, decoded as the reader decodes them.
void appendVtuPoints(const std::string& file, unsigned threads, StepPoints& out) {
  FileBytes bytes = FileBytes::openLazily(file);
  VtuDocument doc(bytes, file, "UnstructuredGrid", threads);
  uint64_t count = 0;
  for (const VtuPiece& p : vtuPieces(doc)) {
    if (p.numPoints == 0) continue;
    pugi::xml_node arr = p.node.child("Points").child("DataArray");
    if (!arr) throw FileError(file, "has a piece of ", p.numPoints, " points but no <Points>");
    const std::vector<glm::dvec3> pts =
        toPoints(doc.decode(arr, p.numPoints, "points", 3), threads);
    out.points.insert(out.points.end(), pts.begin(), pts.end());
    count += pts.size();
  }
  out.pieces.emplace_back(file, count);
}

// -0 and +0 are one position; every other value is compared by its bits.
glm::dvec3 canonical(glm::dvec3 p) {
  return p + glm::dvec3(0.0);
}

uint64_t digestOf(const std::vector<glm::dvec3>& points) {
  Hasher h;
  h.pod(uint64_t(points.size()));
  for (const glm::dvec3& p : points) h.pod(canonical(p));
  return h.digest();
}

// The files whose bytes give a step's points, each with its size and modification time: what
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

// Step 0's digest, computed once per process for each file and pieces while they are unchanged:
// a stream checks every step against it.
uint64_t firstStepDigest(const std::string& file, const ReadOptions& options) {
  static std::mutex mutex;
  static std::map<uint64_t, uint64_t> digests;  // stamp -> digest
  const uint64_t stamp = stampOf(file, options);
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (auto it = digests.find(stamp); it != digests.end()) return it->second;
  }
  const uint64_t digest = digestOf(readStepPoints(file, options).points);
  std::lock_guard<std::mutex> lock(mutex);
  if (digests.size() > 64) digests.clear();  // a process reads a handful of series
  digests[stamp] = digest;
  return digest;
}

// Point `i` of the points read, named by its piece file when `file` has pieces.
std::string pointName(const std::string& file, const StepPoints& s, uint64_t i) {
  if (s.pieces.size() == 1 && s.pieces[0].first == file) return concat("point ", i);
  for (const auto& [file, count] : s.pieces) {
    if (i < count) return concat("point ", i, " of piece '", file, "'");
    i -= count;
  }
  return concat("point ", i);
}

}  // namespace

StepPoints readStepPoints(const std::string& file, const ReadOptions& options) {
  StepPoints out;
  if (fileExtension(file) == ".vtu") {
    appendVtuPoints(file, options.threads, out);
  } else if (isPieceIndex(file)) {
    const std::vector<std::string> files = pvtuPieceFiles(file);
    for (int i : pvtuChosenPieces(file, int(files.size()), options))
      appendVtuPoints(files[size_t(i)], options.threads, out);
  } else {
    ReadOptions o = options;
    o.loadFields = false;
    o.fields.clear();
    o.step.reset();
    out.points = readMesh(file, o).points;
    out.pieces.emplace_back(file, out.points.size());
  }
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

void throwMovedPoint(const std::string& path, uint64_t k, const SeriesStep& step,
                     const std::string& where, const glm::dvec3& first, const glm::dvec3& later) {
  auto xyz = [](const glm::dvec3& p) { return concat("(", p.x, ", ", p.y, ", ", p.z, ")"); };
  throw FileError(path, "step ", k, " ('", step.file, "') has ", where, " at ", xyz(later),
                  ", step 0 at ", xyz(first),
                  ": every step of a series must be the same mesh, its points in the same places "
                  "and order (render the files of a moving or renumbered mesh one at a time)");
}

void checkSamePoints(const std::string& path, const std::vector<SeriesStep>& steps, uint64_t k,
                     const ReadOptions& options) {
  if (k == 0) return;
  const StepPoints later = readStepPoints(steps[k].file, options);
  if (digestOf(later.points) == firstStepDigest(steps[0].file, options)) return;
  const StepPoints first = readStepPoints(steps[0].file, options);
  const std::optional<uint64_t> i = firstMovedPoint(first.points, later.points);
  if (!i) return;  // step 0's files were replaced after its digest was taken
  if (*i >= first.points.size() || *i >= later.points.size())
    throw FileError(path, "step ", k, " ('", steps[k].file, "') has ", later.points.size(),
                    " points, step 0 ", first.points.size(),
                    ": every step of a series must be the same mesh");
  throwMovedPoint(path, k, steps[k], pointName(steps[k].file, later, *i), first.points[*i],
                  later.points[*i]);
}

}  // namespace sm::io
