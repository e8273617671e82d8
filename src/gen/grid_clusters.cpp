// The grid mesh's clusters: rings of sectors whose boundaries wave (so neighbouring clusters
// interlock and a straight line crosses a boundary several times, as with METIS parts of real
// meshes), and one small cluster nested inside another. A cell's cluster is a function of its
// indices alone, so each piece can be made without the others.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <glm/geometric.hpp>

#include "gen/grid_mesh.h"

namespace sm::gen {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kSectorWave = 0.35;             // of a sector's width
const glm::dvec3 kBubbleCentre(3.0, 0.25, 0.1);  // in the wake

}  // namespace

bool GridMesh::Box::holds(int j, int i, int k, int nTheta) const {
  const int di = ((i - i0) % nTheta + nTheta) % nTheta;
  return j >= j0 && j <= j1 && k >= k0 && k <= k1 && di <= i1 - i0;
}

glm::dvec3 GridMesh::cellCentre(int j, int i, int k) const {
  const double r = 0.5 * (radius_[j] + radius_[j + 1]), theta = kTwoPi * (i + 0.5) / nTheta_;
  return {r * std::cos(theta), r * std::sin(theta), zLo_ + (zHi_ - zLo_) * (k + 0.5) / nZ_};
}

// Rings hold whole numbers of sectors and elements in proportion; sectors of neighbouring rings
// are offset by half a sector, so no boundary runs straight through.
void GridMesh::chooseClusters(int clusters) {
  clusters_ = clusters;
  const int layers = radialCells();
  auto rings = [&](int bands) {
    const int n = std::clamp(int(std::lround(std::sqrt(bands / 8.0))), 1, std::max(1, layers / 3));
    const int nRings = std::min(n, bands);
    ringSectors_.assign(nRings, bands / nRings);
    for (int r = 0; r < bands % nRings; ++r) ++ringSectors_[r];
    ringFirst_.assign(nRings, 0);
    for (int r = 1; r < nRings; ++r) ringFirst_[r] = ringFirst_[r - 1] + ringSectors_[r - 1];
    ringCut_.assign(nRings + 1, layers);
    ringCut_[0] = 0;
    uint64_t total = 0, sum = 0;
    for (uint64_t e : elementsByLayer_) total += e;
    int j = 0, sectors = 0;
    for (int r = 1; r < nRings; ++r) {
      sectors += ringSectors_[r - 1];
      const double goal = double(total) * sectors / bands;
      while (j < layers && double(sum) < goal) sum += elementsByLayer_[j++];
      ringCut_[r] = std::clamp(j, ringCut_[r - 1] + 1, layers - (nRings - r));
    }
    int thinnest = layers;
    for (int r = 0; r < nRings; ++r) thinnest = std::min(thinnest, ringCut_[r + 1] - ringCut_[r]);
    ringWave_ = nRings > 1 ? std::min(3.0, 0.3 * thinnest) : 0.0;
  };
  nested_ = host_ = -1;
  if (clusters < 3) return rings(clusters);
  rings(clusters - 1);
  // The nested cluster is a ball well inside its host's band, with a shell of the host around it
  // at least a cell deep, so that it touches no other cluster.
  bubbleCentre_ = kBubbleCentre;
  const int j = radialCellAt(std::hypot(bubbleCentre_.x, bubbleCentre_.y));
  int r = 0;
  while (r + 1 < int(ringSectors_.size()) && j >= ringCut_[r + 1]) ++r;
  const double rc = std::hypot(bubbleCentre_.x, bubbleCentre_.y);
  const double sectorWidth = rc * kTwoPi / ringSectors_[r];
  const double ringDepth = radius_[ringCut_[r + 1]] - radius_[ringCut_[r]];
  const double cell =
      std::max({rc * kTwoPi / nTheta_, (zHi_ - zLo_) / nZ_, radius_[j + 1] - radius_[j]});
  bubbleRadius_ = std::min({0.6, 0.3 * sectorWidth, 0.3 * ringDepth});
  bubbleShell_ = 1.5 * cell;
  if (bubbleRadius_ < 1.5 * cell) return rings(clusters);  // too coarse for a ball
  host_ = bandCluster(
      j,
      std::min(nTheta_ - 1, int(std::atan2(bubbleCentre_.y, bubbleCentre_.x) / kTwoPi * nTheta_)),
      std::min(nZ_ - 1, int((bubbleCentre_.z - zLo_) / (zHi_ - zLo_) * nZ_)));
  nested_ = clusters - 1;
}

int GridMesh::bandCluster(int j, int i, int k) const {
  const double jj =
      j + 0.5 + ringWave_ * std::sin(kTwoPi * (3.0 * i / nTheta_ + 2.0 * double(k) / nZ_));
  int r = 0;
  while (r + 1 < int(ringSectors_.size()) && jj >= ringCut_[r + 1]) ++r;
  const int sectors = ringSectors_[r];
  const double width = double(nTheta_) / sectors;
  const double wave = kSectorWave * width *
                      std::sin(kTwoPi * (4.0 * double(k) / nZ_ + 1.5 * double(j) / radialCells()));
  double u = (i + 0.5 + wave + 0.5 * width * r) / nTheta_;
  u -= std::floor(u);
  return ringFirst_[r] + std::min(sectors - 1, int(u * sectors));
}

int GridMesh::clusterOfCell(int j, int i, int k) const {
  if (nested_ >= 0) {
    const Box b = bubbleBox();
    if (b.holds(j, i, k, nTheta_)) {
      const double d = glm::length(cellCentre(j, i, k) - bubbleCentre_);
      if (d < bubbleRadius_) return nested_;
      if (d < bubbleRadius_ + bubbleShell_) return host_;
    }
  }
  return bandCluster(j, i, k);
}

GridMesh::Box GridMesh::bubbleBox() const {
  const double reach = bubbleRadius_ + bubbleShell_;
  const double rc = std::hypot(bubbleCentre_.x, bubbleCentre_.y);
  const double tc = std::atan2(bubbleCentre_.y, bubbleCentre_.x), dt = std::asin(reach / rc);
  const double dz = (zHi_ - zLo_) / nZ_;
  Box b;
  b.j0 = std::max(0, radialCellAt(rc - reach) - 1);
  b.j1 = std::min(radialCells() - 1, radialCellAt(rc + reach) + 1);
  b.i0 = int(std::floor((tc - dt) / kTwoPi * nTheta_)) - 1;
  b.i1 = int(std::ceil((tc + dt) / kTwoPi * nTheta_)) + 1;
  b.k0 = std::max(0, int(std::floor((bubbleCentre_.z - reach - zLo_) / dz)) - 1);
  b.k1 = std::min(nZ_ - 1, int(std::ceil((bubbleCentre_.z + reach - zLo_) / dz)) + 1);
  return b;
}

std::vector<GridMesh::Box> GridMesh::candidateBoxes(int cluster) const {
  if (cluster == nested_) return {bubbleBox()};
  int r = 0;
  while (r + 1 < int(ringFirst_.size()) && cluster >= ringFirst_[r + 1]) ++r;
  const int sectors = ringSectors_[r], s = cluster - ringFirst_[r];
  const double width = double(nTheta_) / sectors, offset = 0.5 * width * r + 0.5;
  const double amp = kSectorWave * width;
  const int wave = int(std::ceil(ringWave_));
  Box b{std::max(0, ringCut_[r] - wave - 1),
        std::min(radialCells() - 1, ringCut_[r + 1] + wave),
        int(std::floor(s * width - offset - amp)) - 1,
        int(std::ceil((s + 1) * width - offset + amp)) + 1,
        0,
        nZ_ - 1};
  if (b.i1 - b.i0 + 1 >= nTheta_) b.i0 = 0, b.i1 = nTheta_ - 1;
  std::vector<Box> boxes{b};
  if (cluster == host_) boxes.push_back(bubbleBox());
  return boxes;
}

uint64_t GridMesh::largestPieceElements() const {
  // A band's share plus its waves and, for the host, the nested ball's shell: bounded generously
  // by twice an even share; the exact count would need the piece itself.
  const int bands = nested_ >= 0 ? clusters_ - 1 : clusters_;
  return 2 * (elements_ / uint64_t(bands) + 1);
}

namespace {

// Crossings of one line: for each cluster met, how many times the line enters or leaves it.
void countCrossings(const GridMesh& g, const glm::dvec3& from, const glm::dvec3& to, double step,
                    std::vector<int>& crossings) {
  std::fill(crossings.begin(), crossings.end(), 0);
  const int samples = int(glm::length(to - from) / step) + 1;
  int last = -1;
  for (int s = 0; s <= samples; ++s) {
    const int c = g.clusterAt(from + (to - from) * (double(s) / samples));
    if (c == last) continue;
    if (last >= 0) ++crossings[last];
    if (c >= 0) ++crossings[c];
    last = c;
  }
}

bool nestedEnclosed(const GridMesh& g) {
  if (g.nestedCluster() < 0) return false;
  const GridMesh::Box box = g.bubbleBox();
  for (int k = box.k0; k <= box.k1; ++k)
    for (int j = box.j0; j <= box.j1; ++j)
      for (int ii = box.i0; ii <= box.i1; ++ii) {
        const int i = (ii % g.thetaCells() + g.thetaCells()) % g.thetaCells();
        if (g.clusterOfCell(j, i, k) != g.nestedCluster()) continue;
        const int n = g.thetaCells();
        const int nb[6][3] = {{j - 1, i, k},       {j + 1, i, k}, {j, (i + n - 1) % n, k},
                              {j, (i + 1) % n, k}, {j, i, k - 1}, {j, i, k + 1}};
        for (const auto& c : nb) {
          if (c[0] < 0 || c[0] >= g.radialCells() || c[2] < 0 || c[2] >= g.zCells()) return false;
          const int other = g.clusterOfCell(c[0], c[1], c[2]);
          if (other != g.nestedCluster() && other != g.hostCluster()) return false;
        }
      }
  return true;
}

// The part of the line p + s d inside the box (slab clipping); p lies inside.
std::pair<glm::dvec3, glm::dvec3> clipped(const mesh::Bounds& b, const glm::dvec3& p,
                                          const glm::dvec3& d) {
  double lo = -1e300, hi = 1e300;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-12) continue;
    const double s0 = (b.lo[a] - p[a]) / d[a], s1 = (b.hi[a] - p[a]) / d[a];
    lo = std::max(lo, std::min(s0, s1));
    hi = std::min(hi, std::max(s0, s1));
  }
  return {p + d * lo, p + d * hi};
}

}  // namespace

ClusterShapeReport clusterShapes(const GridMesh& g, int linesPerCluster, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const mesh::Bounds b = g.bounds();
  const double step = 0.5 * kTwoPi / g.thetaCells();  // half a cell at the wall
  const int bands = g.nestedCluster() >= 0 ? g.clusters() - 1 : g.clusters();
  std::vector<int> most(g.clusters(), 0), crossings(g.clusters());
  ClusterShapeReport report;
  uint64_t met = 0, total = 0;
  for (int l = 0; l < linesPerCluster * bands; ++l) {
    // Through a point of band l % bands (each band gets its lines), in a random direction.
    const int want = l % bands;
    glm::dvec3 p;
    do p = b.lo + b.extent() * glm::dvec3(unit(rng), unit(rng), unit(rng));
    while (g.clusterAt(p) != want && unit(rng) < 0.99999);
    const double z = 2.0 * unit(rng) - 1.0, a = kTwoPi * unit(rng);
    const glm::dvec3 d(std::sqrt(1 - z * z) * std::cos(a), std::sqrt(1 - z * z) * std::sin(a), z);
    const auto [from, to] = clipped(b, p, d);
    countCrossings(g, from, to, step, crossings);
    for (int c = 0; c < g.clusters(); ++c) {
      most[c] = std::max(most[c], crossings[c]);
      if (crossings[c] > 0) ++met, total += uint64_t(crossings[c]);
    }
    ++report.lines;
  }
  report.meanCrossings = met ? double(total) / double(met) : 0.0;
  report.fewestMostCrossings = *std::min_element(most.begin(), most.begin() + bands);
  report.nestedEnclosed = nestedEnclosed(g);
  return report;
}

}  // namespace sm::gen
