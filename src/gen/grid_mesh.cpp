// The O-grid's layout: node radii, what each cell is split into, and how many elements that makes.
// Cluster shapes are in grid_clusters.cpp, the elements of a piece in grid_piece.cpp.
#include "gen/grid_mesh.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/check.h"
#include "common/error.h"

namespace sm::gen {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kOuterRadius = 15.0;
constexpr int kMinTheta = 24;
// Kuhn's six tetrahedra per cell; a transition cell is one pyramid on the hexahedron below and ten
// tetrahedra on its other five faces, around its centre.
constexpr uint64_t kTetsPerCell = 6, kTransitionTets = 10;

}  // namespace

GridMesh::GridMesh(const GridMeshOptions& options) : steps_(options.steps) {
  if (options.targetElements < 10000 || options.targetElements > 2000000000ull)
    throw Error("--elements: the grid generator makes 10000 to 2000000000 elements, got ",
                options.targetElements);
  if (options.steps < 1) throw Error("--steps: must be at least 1, got ", options.steps);
  if (options.clusters < 0) throw Error("--clusters: must not be negative, got ", options.clusters);
  chooseGrid(options.targetElements);
  const uint64_t automatic = std::max<uint64_t>(8, (elements_ + 3999999) / 4000000);
  chooseClusters(options.clusters > 0 ? options.clusters : int(automatic));
}

// Radii grow geometrically in the boundary layer (first layer 1/50 of the last) and then
// logarithmically, so that outer cells are about as deep as they are wide (r dtheta).
void GridMesh::chooseGrid(uint64_t target) {
  auto layout = [this](int nTheta) {
    nTheta_ = nTheta;
    nZ_ = nTheta / 4;
    const double h = kTwoPi / nTheta;
    const int outer = std::max(4, int(std::lround(std::log(kOuterRadius) / h)));
    nLayers_ = std::max(2, outer / 2);
    const double q = std::pow(50.0, 1.0 / (nLayers_ - 1));
    radius_.assign(1, 1.0);
    for (int m = 0; m < nLayers_; ++m)
      radius_.push_back(radius_.back() + h * std::pow(q, m - (nLayers_ - 1)));
    const double wall = radius_.back(), step = std::log(kOuterRadius / wall) / outer;
    for (int m = 1; m < outer; ++m) radius_.push_back(wall * std::exp(step * m));
    radius_.push_back(kOuterRadius);
    return countElements(typeCounts_);
  };
  // About 0.7 nTheta^3 elements: start the search a little below.
  int n = std::max(kMinTheta, 4 * (int(std::cbrt(double(target) / 0.75)) / 4) - 8);
  uint64_t below = layout(n);
  while (below < target) {
    const uint64_t above = layout(n + 4);
    if (above >= target) {
      if (target - below < above - target) layout(n);
      break;
    }
    n += 4;
    below = above;
  }
  elements_ = countElements(typeCounts_);
  const uint64_t pointsPerPiece = points();
  if (pointsPerPiece > 0xFFFFFFFFull)
    throw Error("--elements: ", target, " elements need ", pointsPerPiece,
                " points, more than 32-bit ids hold");
}

GridCell GridMesh::cellKind(int j, int i) const {
  const bool leeward = std::cos(kTwoPi * (i + 0.5) / nTheta_) > 0.5;  // |theta| < 60 degrees
  if (j < nLayers_) return leeward ? GridCell::Hex : GridCell::Wedges;
  if (j == nLayers_ && leeward) return GridCell::Transition;
  return GridCell::Tets;
}

uint64_t GridMesh::countElements(std::array<uint64_t, mesh::kNumCellTypes>& perType) {
  perType.fill(0);
  elementsByLayer_.assign(radius_.size() - 1, 0);
  for (int j = 0; j + 1 < int(radius_.size()); ++j) {
    std::array<uint64_t, mesh::kNumCellTypes> layer{};
    for (int i = 0; i < nTheta_; ++i) switch (cellKind(j, i)) {
        case GridCell::Wedges:
          layer[mesh::typeIndex(mesh::CellType::Wedge)] += 2;
          break;
        case GridCell::Hex:
          layer[mesh::typeIndex(mesh::CellType::Hex)] += 1;
          break;
        case GridCell::Transition:
          layer[mesh::typeIndex(mesh::CellType::Pyramid)] += 1;
          layer[mesh::typeIndex(mesh::CellType::Tet)] += kTransitionTets;
          break;
        case GridCell::Tets:
          layer[mesh::typeIndex(mesh::CellType::Tet)] += kTetsPerCell;
          break;
      }
    uint64_t sum = 0;
    for (int t = 0; t < mesh::kNumCellTypes; ++t) {
      perType[t] += layer[t] * uint64_t(nZ_);
      sum += layer[t] * uint64_t(nZ_);
    }
    elementsByLayer_[j] = sum;
  }
  uint64_t total = 0;
  for (uint64_t c : perType) total += c;
  return total;
}

uint64_t GridMesh::points() const {
  uint64_t transitions = 0;
  for (int i = 0; i < nTheta_; ++i)
    transitions += cellKind(nLayers_, i) == GridCell::Transition ? uint64_t(nZ_) : 0;
  return uint64_t(radius_.size()) * nTheta_ * (nZ_ + 1) + transitions;
}

mesh::Bounds GridMesh::bounds() const {
  mesh::Bounds b;
  b.extend({-kOuterRadius, -kOuterRadius, zLo_});
  b.extend({kOuterRadius, kOuterRadius, zHi_});
  return b;
}

glm::dvec3 GridMesh::node(int j, int i, int k) const {
  const double theta = kTwoPi * double((i % nTheta_ + nTheta_) % nTheta_) / nTheta_;
  const double r = radius_[j];
  return {r * std::cos(theta), r * std::sin(theta), zLo_ + (zHi_ - zLo_) * double(k) / nZ_};
}

int GridMesh::radialCellAt(double r) const {
  auto it = std::upper_bound(radius_.begin(), radius_.end(), r);
  return int(it - radius_.begin()) - 1;
}

int GridMesh::clusterAt(const glm::dvec3& p) const {
  const double r = std::hypot(p.x, p.y);
  if (!(r >= 1.0 && r < kOuterRadius && p.z >= zLo_ && p.z < zHi_)) return -1;
  double theta = std::atan2(p.y, p.x);
  if (theta < 0) theta += kTwoPi;
  const int i = std::min(nTheta_ - 1, int(theta / kTwoPi * nTheta_));
  const int k = std::min(nZ_ - 1, int((p.z - zLo_) / (zHi_ - zLo_) * nZ_));
  return clusterOfCell(radialCellAt(r), i, k);
}

}  // namespace sm::gen
