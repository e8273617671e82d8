#include "synthetic.h"

#include <algorithm>
#include <cmath>

namespace sm::comp::bench {
namespace {

uint32_t mix(uint32_t h) {
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return h;
}

}  // namespace

SyntheticScene::SyntheticScene(int width, int height, int ranks, uint32_t depthBlocks,
                               uint32_t seed)
    : width_(width), height_(height), ranks_(ranks) {
  g_ = depthBlocks ? depthBlocks
                   : std::max(12u, uint32_t(std::ceil(std::cbrt(4.0 * double(ranks)))));
  owner_.resize(size_t(g_) * g_ * g_);
  for (size_t b = 0; b < owner_.size(); ++b) owner_[b] = int(mix(uint32_t(b) ^ mix(seed)) % ranks);
}

bool SyntheticScene::chord(int x, int y, double& z0, double& z1, uint32_t& column) const {
  const double s = 0.9 * std::min(width_, height_);  // ball diameter in pixels
  double u = (2.0 * (x + 0.5) - width_) / s, v = (2.0 * (y + 0.5) - height_) / s;
  double r2 = u * u + v * v;
  if (r2 >= 1.0) return false;
  z1 = std::sqrt(1.0 - r2);
  z0 = -z1;
  auto block = [&](double c) { return std::min(g_ - 1, uint32_t((c + 1.0) * 0.5 * g_)); };
  column = block(u) * g_ + block(v);
  return true;
}

// Calls emit(entry, exit) for each run of rank-r blocks along the pixel's chord.
template <typename Emit>
void SyntheticScene::runs(int rank, uint64_t pixel, Emit emit) const {
  double z0, z1;
  uint32_t column;
  if (!chord(int(pixel % uint64_t(width_)), int(pixel / uint64_t(width_)), z0, z1, column)) return;
  const double size = 2.0 / g_;
  const int* owners = &owner_[size_t(column) * g_];
  uint32_t first = std::min(g_ - 1, uint32_t((z0 + 1.0) / size));
  uint32_t last = std::min(g_ - 1, uint32_t((z1 + 1.0) / size));
  double start = 0.0;
  bool inside = false;
  for (uint32_t b = first; b <= last; ++b) {
    bool mine = owners[b] == rank;
    double lo = std::max(z0, -1.0 + b * size);
    if (mine && !inside) start = lo;
    if (!mine && inside) emit(start, lo);
    inside = mine;
  }
  if (inside) emit(start, z1);
}

HostLists SyntheticScene::lists(int rank) const {
  HostLists out;
  const uint64_t pixels = uint64_t(width_) * uint64_t(height_);
  out.counts.resize(pixels);
  for (uint64_t p = 0; p < pixels; ++p) {
    runs(rank, p, [&](double entry, double exit) {
      const float a = float(1.0 - std::exp(-1.5 * (exit - entry)));
      const uint32_t h = mix(uint32_t(p) * 31u + uint32_t(rank));
      glm::vec4 c(float(h & 255) / 255.0f, float((h >> 8) & 255) / 255.0f,
                  float((h >> 16) & 255) / 255.0f, 1.0f);
      out.fragments.push_back({c * a, float(entry + 2.0)});  // depth from an eye at z = -2
      ++out.counts[p];
    });
  }
  return out;
}

void SyntheticScene::counts(int rank, std::vector<uint32_t>& out) const {
  const uint64_t pixels = uint64_t(width_) * uint64_t(height_);
  out.assign(pixels, 0);
  for (uint64_t p = 0; p < pixels; ++p) runs(rank, p, [&](double, double) { ++out[p]; });
}

}  // namespace sm::comp::bench
