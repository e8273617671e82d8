#include "border/border_exchange.h"

#include <algorithm>
#include <array>
#include <bit>
#include <limits>
#include <numeric>
#include <tuple>

#include "common/check.h"
#include "common/error.h"
#include "common/hash.h"
#include "common/log.h"
#include "prep/connectivity.h"

namespace sm::border {
namespace {

// A point's coordinates, bit for bit, and which copy of that position it is on its rank.
using Key = std::array<uint64_t, 4>;
using Position = std::array<uint64_t, 3>;

Position positionOf(const glm::dvec3& p) {
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

// A point's name before its copy number: its coordinates, bit for bit, or its id.
Position nameOf(const mesh::UnstructuredMesh& m, std::span<const uint64_t> ids, uint32_t p) {
  return ids.empty() ? positionOf(m.points[p]) : Position{ids[p], 0, 0};
}

// For each of `border`, how many of the rank's points (any, used or not) of the same name have a
// lower id: the weld joins a piece's k-th copy of a position with the k-th copy of every other
// piece, and a rank's own weld numbers its copies in that order.
std::vector<uint64_t> occurrences(const mesh::UnstructuredMesh& m, std::span<const uint64_t> ids,
                                  const std::vector<uint32_t>& border) {
  std::vector<Position> positions;
  positions.reserve(border.size());
  for (uint32_t p : border) positions.push_back(nameOf(m, ids, p));
  std::sort(positions.begin(), positions.end());
  positions.erase(std::unique(positions.begin(), positions.end()), positions.end());
  std::vector<uint64_t> seen(positions.size(), 0), occ;
  occ.reserve(border.size());
  size_t next = 0;  // border is in increasing order
  for (uint32_t p = 0; p < m.numPoints() && next < border.size(); ++p) {
    const Position key = nameOf(m, ids, p);
    auto it = std::lower_bound(positions.begin(), positions.end(), key);
    if (it == positions.end() || *it != key) continue;
    const uint64_t k = seen[size_t(it - positions.begin())]++;
    if (border[next] == p) {
      occ.push_back(k);
      ++next;
    }
  }
  SM_CHECK_EQ(occ.size(), border.size());
  return occ;
}

int meetingRank(const Key& k, int ranks) {
  return int(hashBytes(k.data(), sizeof k) % uint64_t(ranks));
}

}  // namespace

BorderExchange::BorderExchange(const mesh::UnstructuredMesh& m, comm::Communicator& comm,
                               std::span<const uint64_t> pointIds)
    : numPoints_(m.numPoints()) {
  SM_CHECK(pointIds.empty() || pointIds.size() == m.numPoints());
  const int n = comm.size();
  const std::vector<uint32_t> border = boundaryPoints(m);
  const std::vector<uint64_t> occ = occurrences(m, pointIds, border);
  // Offers: the name's words (bit patterns carried in doubles, never computed with) and the copy
  // number, per boundary point, to the point's meeting rank.
  std::vector<std::vector<double>> offers(n);
  std::vector<std::vector<uint32_t>> offered(n);
  for (size_t i = 0; i < border.size(); ++i) {
    const Position pos = nameOf(m, pointIds, border[i]);
    const int to = meetingRank({pos[0], pos[1], pos[2], occ[i]}, n);
    offers[to].insert(offers[to].end(),
                      {std::bit_cast<double>(pos[0]), std::bit_cast<double>(pos[1]),
                       std::bit_cast<double>(pos[2]), double(occ[i])});
    offered[to].push_back(border[i]);
  }
  std::vector<std::vector<double>> got = comm::exchangeValues(comm, offers);
  offers.clear();
  // As meeting rank: a name offered by two or more ranks is a shared point, one group.
  std::vector<std::tuple<Key, int, uint32_t>> entries;
  std::vector<size_t> offeredBy(n);
  for (int s = 0; s < n; ++s) offeredBy[s] = got[s].size() / 4;
  entries.reserve(std::accumulate(offeredBy.begin(), offeredBy.end(), size_t(0)));
  for (int s = 0; s < n; ++s) {
    for (size_t i = 0; i < offeredBy[s]; ++i) {
      const double* e = got[s].data() + 4 * i;
      const Position pos = positionOf({e[0], e[1], e[2]});  // the words sent, as they were
      entries.push_back({{pos[0], pos[1], pos[2], uint64_t(e[3])}, s, uint32_t(i)});
    }
    std::vector<double>().swap(got[s]);
  }
  std::sort(entries.begin(), entries.end());
  std::vector<std::vector<int64_t>> group(n);
  for (int s = 0; s < n; ++s) group[s].assign(offeredBy[s], -1);
  for (size_t a = 0, b; a < entries.size(); a = b) {
    for (b = a + 1; b < entries.size() && std::get<0>(entries[b]) == std::get<0>(entries[a]);) ++b;
    if (b - a < 2) continue;  // on one rank only: the outside of the data, or a local seam
    for (size_t e = a; e < b; ++e)
      group[std::get<1>(entries[e])][std::get<2>(entries[e])] = groups_;
    ++groups_;
  }
  std::vector<std::vector<double>> shared(n);
  groupOf_.resize(n);
  for (int s = 0; s < n; ++s)
    for (int64_t g : group[s]) {
      shared[s].push_back(g >= 0 ? 1.0 : 0.0);
      if (g >= 0) groupOf_[s].push_back(uint32_t(g));
    }
  const std::vector<std::vector<double>> answers = comm::exchangeValues(comm, shared);
  mine_.resize(n);
  for (int to = 0; to < n; ++to) {
    SM_CHECK_EQ(answers[to].size(), offered[to].size());
    for (size_t i = 0; i < offered[to].size(); ++i)
      if (answers[to][i] != 0.0) mine_[to].push_back(offered[to][i]);
    sharedPoints_ += mine_[to].size();
  }
  log::debug(m.source, ": ", border.size(), " points on this rank's boundary, ", sharedPoints_,
             " shared with other ranks");
}

void BorderExchange::addOtherRanks(std::vector<std::vector<double>>& columns,
                                   comm::Communicator& comm) const {
  const size_t width = columns.size();
  for (const auto& c : columns) SM_CHECK_EQ(c.size(), numPoints_);
  const int n = comm.size();
  std::vector<std::vector<double>> values(n);  // per shared point, its value in every column
  for (int to = 0; to < n; ++to) {
    values[to].reserve(mine_[to].size() * width);
    for (uint32_t p : mine_[to])
      for (const auto& c : columns) values[to].push_back(c[p]);
  }
  const std::vector<std::vector<double>> received = comm::exchangeValues(comm, values);
  std::vector<double> totals(groups_ * width, 0.0);
  for (int s = 0; s < n; ++s) {  // in rank order: every copy gets the same sums
    SM_CHECK_EQ(received[s].size(), groupOf_[s].size() * width);
    for (size_t i = 0; i < groupOf_[s].size(); ++i)
      for (size_t k = 0; k < width; ++k)
        totals[groupOf_[s][i] * width + k] += received[s][i * width + k];
  }
  std::vector<std::vector<double>> sums(n);
  for (int s = 0; s < n; ++s)
    for (uint32_t g : groupOf_[s])
      sums[s].insert(sums[s].end(), totals.begin() + ptrdiff_t(g * width),
                     totals.begin() + ptrdiff_t((g + 1) * width));
  const std::vector<std::vector<double>> back = comm::exchangeValues(comm, sums);
  for (int from = 0; from < n; ++from) {
    SM_CHECK_EQ(back[from].size(), mine_[from].size() * width);
    for (size_t i = 0; i < mine_[from].size(); ++i)
      for (size_t k = 0; k < width; ++k) columns[k][mine_[from][i]] = back[from][i * width + k];
  }
}

}  // namespace sm::border
