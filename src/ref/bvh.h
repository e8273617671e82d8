// A bounding volume hierarchy over axis-aligned boxes, in double precision: the reference
// renderer's only acceleration structure. It answers "which boxes may this ray touch" and never
// misses one (boundaries count as touching, the slab test is widened by a few ulps), so the
// reference stays brute force in what it computes and only skips work that cannot matter.
// Built by median splits of box centres along the widest axis: O(n log n), about a second per
// million boxes, and depth log2(n / leafSize).
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace sm::ref {

struct Box {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()};
  glm::dvec3 hi{-std::numeric_limits<double>::infinity()};
  void extend(const glm::dvec3& p);
  void extend(const Box& b);
  bool empty() const { return !(lo.x <= hi.x); }
};

class Bvh {
 public:
  Bvh() = default;
  explicit Bvh(std::span<const Box> boxes, uint32_t leafSize = 4);

  // Appends to `out` the index of every box that the half-line origin + t dir (t >= 0) touches.
  void query(const glm::dvec3& origin, const glm::dvec3& dir, std::vector<uint32_t>& out) const;

  size_t numNodes() const { return nodes_.size(); }
  int depth() const { return depth_; }

 private:
  struct Node {
    Box box;
    uint32_t offset = 0;  // leaf: first entry in prims_; interior: index of the right child
    uint32_t count = 0;   // leaf: number of boxes; 0 for interior nodes (left child = next node)
  };
  uint32_t build(uint32_t begin, uint32_t end, std::span<const Box> boxes,
                 std::span<const glm::dvec3> centres, uint32_t leafSize, int level);

  std::vector<Node> nodes_;
  std::vector<uint32_t> prims_;
  int depth_ = 0;
};

}  // namespace sm::ref
