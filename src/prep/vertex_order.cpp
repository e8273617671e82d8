#include "prep/vertex_order.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "common/check.h"

namespace sm::prep {
namespace {

uint64_t spread21(uint64_t x) {
  x &= 0x1FFFFF;
  x = (x | x << 32) & 0x1F00000000FFFFull;
  x = (x | x << 16) & 0x1F0000FF0000FFull;
  x = (x | x << 8) & 0x100F00F00F00F00Full;
  x = (x | x << 4) & 0x10C30C30C30C30C3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

uint64_t quantise(double v, double lo, double hi) {
  if (!(hi > lo)) return 0;
  // Halved (exactly), so that bounds wider than the largest double, such as -1e308 .. 1e308, give
  // a finite ratio; a NaN left over must not reach the integer conversion.
  double q = (0.5 * v - 0.5 * lo) / (0.5 * hi - 0.5 * lo) * 2097151.0;
  return q > 0.0 ? uint64_t(std::min(q, 2097151.0)) : 0;
}

}  // namespace

GlobalFrame makeGlobalFrame(const mesh::Bounds& b) {
  GlobalFrame f;
  f.bounds = b;
  f.origin = b.empty ? glm::dvec3(0.0) : b.center();
  // The device's exact predicates multiply up to three coordinates in float: sides far from 1
  // (1e13 or 1e-18 units, say) overflow or underflow there and rays find nothing. A power of two
  // brings such a data set's largest side to [1, 2) without rounding any coordinate; data sets of
  // ordinary size keep scale 1 (and their device coordinates bit for bit).
  const glm::dvec3 side = b.empty ? glm::dvec3(0.0) : b.hi - b.lo;
  const double extent = std::max({side.x, side.y, side.z});
  if (extent > 0.0 && std::isfinite(extent) && (extent < 0x1p-20 || extent > 0x1p20))
    f.scale = std::ldexp(1.0, -std::ilogb(extent));
  return f;
}

uint64_t mortonCode(const glm::dvec3& p, const mesh::Bounds& b) {
  return spread21(quantise(p.x, b.lo.x, b.hi.x)) | spread21(quantise(p.y, b.lo.y, b.hi.y)) << 1 |
         spread21(quantise(p.z, b.lo.z, b.hi.z)) << 2;
}

std::vector<uint32_t> globalVertexOrder(const std::vector<glm::dvec3>& points,
                                        const GlobalFrame& frame) {
  struct Key {
    uint64_t morton;
    uint32_t index;
  };
  std::vector<Key> keys(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    keys[i] = {mortonCode(points[i], frame.bounds), uint32_t(i)};
  std::sort(keys.begin(), keys.end(), [&](const Key& a, const Key& b) {
    if (a.morton != b.morton) return a.morton < b.morton;
    const glm::dvec3 &p = points[a.index], &q = points[b.index];
    if (p.x != q.x) return p.x < q.x;
    if (p.y != q.y) return p.y < q.y;
    if (p.z != q.z) return p.z < q.z;
    return a.index < b.index;
  });
  std::vector<uint32_t> order(points.size());
  for (size_t i = 0; i < keys.size(); ++i) order[i] = keys[i].index;
  return order;
}

void orderElementsByVertex(ElementArrays& elements, uint32_t numVertices) {
  std::vector<uint32_t> start;
  for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t) {
    const uint32_t nv = gpu::SM_NUM_VERTS[t];
    std::vector<uint32_t>& cells = elements[t];
    const size_t n = cells.size() / nv;
    if (n < 2) continue;
    auto key = [&](size_t e) { return *std::min_element(&cells[e * nv], &cells[e * nv] + nv); };
    // Counting sort on the key: linear, and stable, so the order is a function of the input.
    start.assign(size_t(numVertices) + 1, 0);
    for (size_t e = 0; e < n; ++e) {
      const uint32_t k = key(e);
      SM_CHECK_LT(k, numVertices);
      ++start[k + 1];
    }
    std::partial_sum(start.begin(), start.end(), start.begin());
    std::vector<uint32_t> sorted(cells.size());
    for (size_t e = 0; e < n; ++e) {
      const size_t to = start[key(e)]++;
      std::copy_n(&cells[e * nv], nv, &sorted[to * nv]);
    }
    cells.swap(sorted);
  }
}

}  // namespace sm::prep
