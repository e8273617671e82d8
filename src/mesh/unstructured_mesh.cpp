#include "mesh/unstructured_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include <glm/common.hpp>

#include "common/check.h"
#include "common/error.h"
#include "mesh/mesh_builder.h"

namespace sm::mesh {

void Range::extend(double v) {
  if (!std::isfinite(v)) return;
  if (empty) {
    lo = hi = v;
    empty = false;
  } else {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
}

void Range::extend(const Range& r) {
  if (r.empty) return;
  extend(r.lo);
  extend(r.hi);
}

void SkippedCells::add(const SkippedCells& s) {
  surface += s.surface;
  lineOrVertex += s.lineOrVertex;
  polyhedra += s.polyhedra;
  other += s.other;
  quadraticReduced += s.quadraticReduced;
  polyhedraSplit += s.polyhedraSplit;
  polyhedronTets += s.polyhedronTets;
}

uint64_t UnstructuredMesh::numCells() const {
  uint64_t n = 0;
  for (CellType t : kAllCellTypes) n += numCells(t);
  return n;
}

int32_t UnstructuredMesh::numClusters() const {
  int32_t m = -1;
  for (const auto& c : clusters)
    for (int32_t id : c) m = std::max(m, id);
  return m + 1;
}

std::vector<uint8_t> usedPoints(const UnstructuredMesh& m) {
  std::vector<uint8_t> used(m.points.size(), 0);
  for (const auto& ids : m.cells)
    for (uint32_t id : ids) {
      SM_CHECK_LT(id, m.points.size());  // builders check every id against the points
      used[id] = 1;
    }
  return used;
}

Bounds UnstructuredMesh::bounds() const {
  // Points no element uses (those of skipped 2D, line and vertex cells, a quadratic cell's
  // mid-edge nodes) are left out: a stray far point must not shrink the view of the volume.
  const std::vector<uint8_t> used = usedPoints(*this);
  Bounds b;
  for (size_t i = 0; i < points.size(); ++i)
    if (used[i]) b.extend(points[i]);
  return b;
}

const Field* UnstructuredMesh::findField(const std::string& name) const {
  for (const auto& f : fields)
    if (f.name == name) return &f;
  return nullptr;
}

uint64_t UnstructuredMesh::numSteps() const {
  uint64_t n = 0;
  for (const auto& f : fields) n = std::max<uint64_t>(n, f.numSteps());
  return n;
}

Range fieldRange(const Field& f, uint64_t step) {
  Range r;
  if (step >= f.steps.size()) return r;
  for (float v : f.steps[step]) r.extend(v);
  return r;
}

Range fieldRange(const Field& f) {
  Range r;
  for (uint64_t s = 0; s < f.steps.size(); ++s) r.extend(fieldRange(f, s));
  return r;
}

void append(UnstructuredMesh& a, const UnstructuredMesh& b) {
  if (a.points.empty() && a.numCells() == 0 && a.fields.empty()) {
    std::string source = a.source;
    a = b;
    if (!source.empty()) a.source = source;
    return;
  }
  if (a.fields.size() != b.fields.size())
    throw Error(b.source, ": has ", b.fields.size(), " point fields but the first piece has ",
                a.fields.size());
  // Cell fields are averaged onto points where each mesh is read, before any append.
  SM_CHECK(a.cellFields.empty() && b.cellFields.empty());
  uint64_t offset = a.points.size();
  checkPointCount(b.source, offset + b.points.size(), "appended, a mesh would hold",
                  "use more ranks");
  for (size_t i = 0; i < a.fields.size(); ++i) {
    const Field* fb = b.findField(a.fields[i].name);
    if (!fb) throw Error(b.source, ": has no point field '", a.fields[i].name, "'");
    if (fb->numSteps() != a.fields[i].numSteps())
      throw Error(b.source, ": field '", fb->name, "' has ", fb->numSteps(), " time steps, not ",
                  a.fields[i].numSteps());
    for (uint64_t s = 0; s < fb->numSteps(); ++s)
      a.fields[i].steps[s].insert(a.fields[i].steps[s].end(), fb->steps[s].begin(),
                                  fb->steps[s].end());
  }
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  a.pointOrigin.clear();  // the points of a and b may come from different reads
  a.cellOrigin.clear();
  a.fileCells = 0;
  for (int t = 0; t < kNumCellTypes; ++t) {
    a.cells[t].reserve(a.cells[t].size() + b.cells[t].size());
    for (uint32_t id : b.cells[t]) a.cells[t].push_back(static_cast<uint32_t>(id + offset));
    a.clusters[t].insert(a.clusters[t].end(), b.clusters[t].begin(), b.clusters[t].end());
  }
  if (a.timeValues.empty()) a.timeValues = b.timeValues;
  if (a.cellArrays.empty()) a.cellArrays = b.cellArrays;
  a.skipped.add(b.skipped);
  a.invertedFixed += b.invertedFixed;
}

std::string cellArrayHint(const std::vector<std::string>& cellArrays, const std::string& name) {
  if (cellArrays.empty()) return {};
  if (name.empty()) {
    std::string names;
    for (const auto& n : cellArrays) names += (names.empty() ? "" : ", ") + n;
    return concat("; its cell data (", names,
                  ") is read when --field names it, averaged onto the points");
  }
  // "NAME[k]" asks for a component of NAME.
  const std::string base = name.back() == ']' ? name.substr(0, name.rfind('[')) : name;
  if (std::find(cellArrays.begin(), cellArrays.end(), base) == cellArrays.end()) return {};
  return concat("; '", base, "' is cell data, read only when --field names it");
}

namespace {

// Calls use(point, type index, index within the type, element) for every vertex of every element
// (elements counted type by type, in the order of `cells`), once per cell of the file at a point:
// the tetrahedra a polyhedron was split into (consecutive, with one cell origin) count once at a
// point they share, as the polyhedron does in ParaView's Cell Data to Point Data, not once per
// tetrahedron.
template <class Use>
void forEachCellUse(const UnstructuredMesh& m, uint64_t numPoints, Use&& use) {
  const bool split = m.skipped.polyhedraSplit > 0 && m.cellOrigin.size() == m.numCells();
  std::vector<uint32_t> lastOrigin(split ? numPoints : 0, 0xFFFFFFFFu);
  size_t element = 0;
  for (int t = 0; t < kNumCellTypes; ++t) {
    const uint32_t nv = numVerts(kAllCellTypes[t]);
    const std::vector<uint32_t>& ids = m.cells[t];
    for (size_t i = 0; i < ids.size(); i += nv, ++element)
      for (uint32_t k = 0; k < nv; ++k) {
        const uint32_t v = ids[i + k];
        if (split) {
          if (lastOrigin[v] == m.cellOrigin[element]) continue;
          lastOrigin[v] = m.cellOrigin[element];
        }
        use(v, t, i / nv, element);
      }
  }
}

}  // namespace

uint64_t nonFiniteCells(std::span<const float> perElement, std::span<const uint32_t> origins) {
  SM_CHECK(origins.empty() || origins.size() == perElement.size());
  uint64_t n = 0;
  for (size_t i = 0; i < perElement.size(); ++i)
    if (!std::isfinite(perElement[i]) &&
        (origins.empty() || i == 0 || origins[i] != origins[i - 1] ||
         std::isfinite(perElement[i - 1])))
      ++n;
  return n;
}

std::vector<double> cellUsesAtPoints(const UnstructuredMesh& m) {
  std::vector<double> uses(m.numPoints(), 0.0);
  forEachCellUse(m, m.numPoints(), [&](uint32_t v, int, size_t, size_t) { uses[v] += 1.0; });
  return uses;
}

std::vector<double> cellSumsAtPoints(const UnstructuredMesh& m, std::span<const float> perElement,
                                     uint64_t numPoints) {
  SM_CHECK_EQ(perElement.size(), m.numCells());
  std::vector<double> sum(numPoints, 0.0);
  forEachCellUse(m, numPoints, [&](uint32_t v, int, size_t, size_t e) { sum[v] += perElement[e]; });
  return sum;
}

std::vector<double> cellSumsAtPoints(const UnstructuredMesh& m, const CellField& f, size_t step) {
  const auto& perType = f.steps[step];
  for (int t = 0; t < kNumCellTypes; ++t)
    SM_CHECK_EQ(perType[t].size() * numVerts(kAllCellTypes[t]), m.cells[t].size());
  std::vector<double> sum(m.numPoints(), 0.0);
  forEachCellUse(m, m.numPoints(),
                 [&](uint32_t v, int t, size_t i, size_t) { sum[v] += perType[t][i]; });
  return sum;
}

std::vector<float> meansAtPoints(const std::vector<double>& sums, const std::vector<double>& uses) {
  SM_CHECK_EQ(sums.size(), uses.size());
  std::vector<float> values(sums.size());
  for (size_t p = 0; p < values.size(); ++p)
    values[p] = uses[p] > 0 ? float(sums[p] / uses[p]) : std::numeric_limits<float>::quiet_NaN();
  return values;
}

void cellFieldsToPoints(UnstructuredMesh& m) {
  const std::vector<double> uses = cellUsesAtPoints(m);
  for (CellField& cf : m.cellFields) {
    Field f{cf.name, {}};
    for (size_t s = 0; s < cf.steps.size(); ++s)
      f.steps.push_back(meansAtPoints(cellSumsAtPoints(m, cf, s), uses));
    m.fields.push_back(std::move(f));
  }
  m.cellFields.clear();
}

void pointFieldsToCells(UnstructuredMesh& m) {
  for (Field& f : m.fields) {
    CellField cf{f.name, decltype(cf.steps)(f.steps.size())};
    for (size_t s = 0; s < f.steps.size(); ++s)
      for (int t = 0; t < kNumCellTypes; ++t) {
        const uint32_t nv = numVerts(kAllCellTypes[t]);
        const std::vector<uint32_t>& ids = m.cells[t];
        std::vector<float>& out = cf.steps[s][t];
        out.reserve(ids.size() / nv);
        for (size_t i = 0; i < ids.size(); i += nv) {
          double sum = 0;
          for (uint32_t k = 0; k < nv; ++k) sum += f.steps[s][ids[i + k]];
          out.push_back(float(sum / nv));
        }
      }
    m.cellFields.push_back(std::move(cf));
  }
  m.fields.clear();
}

}  // namespace sm::mesh
