// Synthetic fragment lists with the structure of a non-convexly partitioned volume: a ball seen
// along z (orthographic), cut into G x G x G blocks that are dealt to ranks by a hash, so that
// clusters interleave along rays as solver partitions do. A ray yields one fragment per run of
// consecutive blocks of one rank: several fragments per pixel, a handful per rank, none outside the
// ball's silhouette. Colour and opacity grow with a segment's length.
#pragma once

#include <cstdint>
#include <vector>

#include "compositor/host_lists.h"

namespace sm::comp::bench {

class SyntheticScene {
 public:
  // depthBlocks = 0: max(12, cbrt(4 ranks)) blocks along each axis, at least 4 blocks per rank.
  SyntheticScene(int width, int height, int ranks, uint32_t depthBlocks = 0, uint32_t seed = 7);
  int width() const { return width_; }
  int height() const { return height_; }
  uint32_t blocks() const { return g_; }
  // Rank r's lists (front to back).
  HostLists lists(int rank) const;
  // Rank r's per-pixel fragment counts only (fast enough for hundreds of ranks).
  void counts(int rank, std::vector<uint32_t>& out) const;

 private:
  // The ray of pixel (x, y) covers depth [z0, z1] of the ball in [-1, 1]^3; false outside it.
  bool chord(int x, int y, double& z0, double& z1, uint32_t& column) const;
  template <typename Emit>
  void runs(int rank, uint64_t pixel, Emit emit) const;
  int width_, height_, ranks_;
  uint32_t g_;
  std::vector<int> owner_;  // rank of block (column * g + z)
};

}  // namespace sm::comp::bench
