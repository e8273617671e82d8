#include "ref/bvh.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/common.hpp>

#include "common/check.h"

namespace sm::ref {

namespace {

constexpr int kMaxStack = 128;
// Widening of the slab test: a few ulps, so that rounding in (bound - origin) / dir never turns a
// touching ray into a miss (pbrt's 1 + 2 gamma(3)).
constexpr double kWiden = 8.0 * std::numeric_limits<double>::epsilon();

struct RayQuery {
  glm::dvec3 origin, dir, inv;
  bool touches(const Box& b) const {
    double t0 = -std::numeric_limits<double>::infinity();
    double t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      if (dir[a] == 0.0) {  // parallel to the slab: inside it or never
        if (origin[a] < b.lo[a] || origin[a] > b.hi[a]) return false;
        continue;
      }
      double ta = (b.lo[a] - origin[a]) * inv[a], tb = (b.hi[a] - origin[a]) * inv[a];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta - std::abs(ta) * kWiden);
      t1 = std::min(t1, tb + std::abs(tb) * kWiden);
    }
    return t0 <= t1 && t1 >= 0.0;
  }
};

}  // namespace

void Box::extend(const glm::dvec3& p) {
  lo = glm::min(lo, p);
  hi = glm::max(hi, p);
}

void Box::extend(const Box& b) {
  lo = glm::min(lo, b.lo);
  hi = glm::max(hi, b.hi);
}

Bvh::Bvh(std::span<const Box> boxes, uint32_t leafSize) {
  SM_CHECK_GE(leafSize, 1u);
  SM_CHECK_LT(boxes.size(), size_t(std::numeric_limits<uint32_t>::max()));
  if (boxes.empty()) return;
  std::vector<glm::dvec3> centres(boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i) centres[i] = (boxes[i].lo + boxes[i].hi) * 0.5;
  prims_.resize(boxes.size());
  std::iota(prims_.begin(), prims_.end(), 0u);
  nodes_.reserve(2 * boxes.size() / leafSize + 1);
  build(0, uint32_t(boxes.size()), boxes, centres, leafSize, 1);
}

uint32_t Bvh::build(uint32_t begin, uint32_t end, std::span<const Box> boxes,
                    std::span<const glm::dvec3> centres, uint32_t leafSize, int level) {
  depth_ = std::max(depth_, level);
  const uint32_t index = uint32_t(nodes_.size());
  nodes_.emplace_back();
  Box bounds, centreBounds;
  for (uint32_t i = begin; i < end; ++i) {
    bounds.extend(boxes[prims_[i]]);
    centreBounds.extend(centres[prims_[i]]);
  }
  nodes_[index].box = bounds;
  if (end - begin <= leafSize) {
    nodes_[index].offset = begin;
    nodes_[index].count = end - begin;
    return index;
  }
  glm::dvec3 extent = centreBounds.hi - centreBounds.lo;
  int axis = extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
  uint32_t mid = begin + (end - begin) / 2;
  // Equal centres (extent 0) are split by index, which keeps the depth logarithmic.
  if (extent[axis] > 0.0) {
    std::nth_element(prims_.begin() + begin, prims_.begin() + mid, prims_.begin() + end,
                     [&](uint32_t a, uint32_t b) { return centres[a][axis] < centres[b][axis]; });
  }
  build(begin, mid, boxes, centres, leafSize, level + 1);
  uint32_t right = build(mid, end, boxes, centres, leafSize, level + 1);
  nodes_[index].offset = right;
  return index;
}

void Bvh::query(const glm::dvec3& origin, const glm::dvec3& dir, std::vector<uint32_t>& out) const {
  if (nodes_.empty()) return;
  SM_CHECK_LE(depth_, kMaxStack);
  RayQuery q{origin, dir, 1.0 / dir};
  uint32_t stack[kMaxStack];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!q.touches(node.box)) continue;
    if (node.count > 0) {
      out.insert(out.end(), prims_.begin() + node.offset,
                 prims_.begin() + node.offset + node.count);
    } else {
      stack[top++] = node.offset;
      stack[top++] = uint32_t(&node - nodes_.data()) + 1;
    }
  }
}

}  // namespace sm::ref
