#include "app/border_exchange.h"

#include <algorithm>
#include <array>
#include <bit>
#include <limits>

#include "common/check.h"
#include "common/error.h"
#include "common/hash.h"
#include "common/log.h"
#include "prep/connectivity.h"

namespace sm::app {
namespace {

using Key = std::array<uint64_t, 3>;  // a point's coordinates, bit for bit

Key keyOf(const glm::dvec3& p) {
  return {std::bit_cast<uint64_t>(p.x), std::bit_cast<uint64_t>(p.y), std::bit_cast<uint64_t>(p.z)};
}

// The points of the faces no other element of `m` shares, in increasing order.
std::vector<uint32_t> boundaryPoints(const mesh::UnstructuredMesh& m) {
  if (m.numCells() == 0) return {};
  prep::ElementArrays neighbors;
  prep::computeConnectivity(m.cells, m.numPoints(), neighbors, m.source,
                            [&](uint32_t v) { return m.points[v]; });
  std::vector<uint8_t> onBoundary(m.numPoints(), 0);
  for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t) {
    const uint32_t nv = gpu::SM_NUM_VERTS[t], nf = gpu::SM_NUM_FACES[t];
    for (uint64_t e = 0; e * nv < m.cells[t].size(); ++e)
      for (uint32_t s = 0; s < nf; ++s) {
        if (neighbors[t][e * nf + s] != gpu::SM_NO_NEIGHBOR) continue;
        uint32_t f[4];
        const uint32_t n = prep::FaceSlots::faceVertices(t, m.cells[t].data() + e * nv, s, f);
        for (uint32_t k = 0; k < n; ++k) onBoundary[f[k]] = 1;
      }
  }
  std::vector<uint32_t> points;
  for (uint32_t p = 0; p < onBoundary.size(); ++p)
    if (onBoundary[p]) points.push_back(p);
  return points;
}

// {lo.x, lo.y, lo.z, hi.x, hi.y, hi.z}, or nothing for no points.
std::vector<double> boxOf(const mesh::UnstructuredMesh& m, const std::vector<uint32_t>& points) {
  if (points.empty()) return {};
  mesh::Bounds b;
  for (uint32_t p : points) b.extend(m.points[p]);
  return {b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z};
}

bool inBox(const glm::dvec3& p, const std::vector<double>& box) {
  return box.size() == 6 && p.x >= box[0] && p.y >= box[1] && p.z >= box[2] && p.x <= box[3] &&
         p.y <= box[4] && p.z <= box[5];
}

// For each point in `coords` (x, y, z after one another), the first of `points` at bitwise the
// same place, or -1.
std::vector<int64_t> matchPoints(const mesh::UnstructuredMesh& m,
                                 const std::vector<uint32_t>& points,
                                 const std::vector<double>& coords) {
  std::vector<std::pair<Key, uint32_t>> sorted;
  sorted.reserve(points.size());
  for (uint32_t p : points) sorted.push_back({keyOf(m.points[p]), p});
  std::sort(sorted.begin(), sorted.end());  // equal keys: the lowest point id first
  std::vector<int64_t> match(coords.size() / 3, -1);
  for (size_t i = 0; i < match.size(); ++i) {
    const Key k = keyOf({coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]});
    auto it = std::lower_bound(sorted.begin(), sorted.end(), std::pair<Key, uint32_t>{k, 0});
    if (it != sorted.end() && it->first == k) match[i] = it->second;
  }
  return match;
}

}  // namespace

BorderExchange::BorderExchange(const mesh::UnstructuredMesh& m, Collectives& coll) {
  const int n = coll.size(), me = coll.rank();
  const std::vector<uint32_t> border = boundaryPoints(m);
  const std::vector<std::vector<double>> boxes =
      coll.exchange(std::vector<std::vector<double>>(n, boxOf(m, border)));
  send_.resize(n);
  std::vector<std::vector<double>> coords(n);
  for (int d = 0; d < n; ++d) {
    if (d == me) continue;
    for (uint32_t p : border)
      if (inBox(m.points[p], boxes[d])) {
        send_[d].push_back(p);
        coords[d].insert(coords[d].end(), {m.points[p].x, m.points[p].y, m.points[p].z});
      }
  }
  const std::vector<std::vector<double>> offered = coll.exchange(coords);
  match_.resize(n);
  std::vector<uint8_t> matched(m.numPoints(), 0);
  for (int s = 0; s < n; ++s) {
    match_[s] = matchPoints(m, border, offered[s]);
    for (int64_t p : match_[s])
      if (p >= 0) matched[p] = 1;
  }
  shared_ = uint64_t(std::count(matched.begin(), matched.end(), uint8_t(1)));
  log::debug(m.source, ": ", border.size(), " points on this rank's boundary, ", shared_,
             " shared with other ranks");
}

void BorderExchange::addOtherRanks(std::vector<double>& perPoint, Collectives& coll) const {
  const int n = coll.size();
  std::vector<std::vector<double>> values(n);
  for (int d = 0; d < n; ++d) {
    values[d].reserve(send_[d].size());
    for (uint32_t p : send_[d]) values[d].push_back(perPoint[p]);
  }
  const std::vector<std::vector<double>> received = coll.exchange(values);
  for (int s = 0; s < n; ++s) {
    // A rank that sent a different count than it offered broke the protocol: an invariant.
    SM_CHECK_EQ(received[s].size(), match_[s].size());
    for (size_t i = 0; i < received[s].size(); ++i)
      if (match_[s][i] >= 0) perPoint[match_[s][i]] += received[s][i];
  }
}

namespace {

// What every rank must agree on: the cell fields' names and step counts, as a 52-bit number
// (exact in a double, so that ranks can compare it through min and max).
double cellFieldSignature(const mesh::UnstructuredMesh& m) {
  std::string text;
  for (const mesh::CellField& f : m.cellFields)
    text += f.name + '\n' + std::to_string(f.steps.size()) + '\n';
  return double(hashBytes(text.data(), text.size()) & ((uint64_t(1) << 52) - 1));
}

uint64_t cellFieldSteps(const mesh::UnstructuredMesh& m) {
  uint64_t steps = 0;
  for (const mesh::CellField& f : m.cellFields) steps += f.steps.size();
  return steps;
}

}  // namespace

void cellDataToPointsOverRanks(mesh::UnstructuredMesh& m, Collectives& coll) {
  // A rank that read no pieces has no cell fields and no say; it takes part in every round.
  const bool holds = !m.cellFields.empty();
  const double signature = cellFieldSignature(m);
  const double lo = coll.min(holds ? signature : std::numeric_limits<double>::infinity());
  const double hi = coll.max(holds ? signature : -1.0);
  if (hi >= 0 && lo != hi)
    throw Error(m.source, ": the pieces on different ranks do not have the same cell data (",
                "names or time steps); every piece must hold the cell data asked for");
  const uint64_t rounds = uint64_t(coll.max(double(cellFieldSteps(m))));
  BorderExchange border(m, coll);
  std::vector<double> uses = mesh::cellUsesAtPoints(m);
  border.addOtherRanks(uses, coll);
  if (!holds) {
    std::vector<double> none;
    for (uint64_t r = 0; r < rounds; ++r) border.addOtherRanks(none, coll);
    return;
  }
  for (const mesh::CellField& cf : m.cellFields) {
    mesh::Field f{cf.name, {}};
    for (size_t s = 0; s < cf.steps.size(); ++s) {
      std::vector<double> sums = mesh::cellSumsAtPoints(m, cf, s);
      border.addOtherRanks(sums, coll);
      f.steps.push_back(mesh::meansAtPoints(sums, uses));
    }
    m.fields.push_back(std::move(f));
  }
  m.cellFields.clear();
}

}  // namespace sm::app
