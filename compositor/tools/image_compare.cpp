#include "compositor/tools/image_compare.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sm::comp {
namespace {

// Control points of the ramp, evenly spaced in [0, 1].
constexpr std::array<glm::vec4, 5> kRamp = {{{0.0f, 0.0f, 0.0f, 1.0f},
                                             {0.34f, 0.06f, 0.43f, 1.0f},
                                             {0.73f, 0.21f, 0.33f, 1.0f},
                                             {0.98f, 0.55f, 0.04f, 1.0f},
                                             {0.99f, 1.0f, 0.64f, 1.0f}}};

glm::vec4 ramp(float x) {
  if (!(x > 0.0f)) return kRamp.front();  // also NaN
  x = std::min(x, 1.0f) * float(kRamp.size() - 1);
  size_t i = std::min(size_t(x), kRamp.size() - 2);
  float f = x - float(i);
  return kRamp[i] * (1.0f - f) + kRamp[i + 1] * f;
}

}  // namespace

std::vector<float> l2Difference(std::span<const glm::vec4> a, std::span<const glm::vec4> b) {
  if (a.size() != b.size())
    throw std::invalid_argument("l2 difference of images with " + std::to_string(a.size()) +
                                " and " + std::to_string(b.size()) + " pixels");
  std::vector<float> d(a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    glm::vec4 e = a[i] - b[i];
    d[i] = std::sqrt(e.x * e.x + e.y * e.y + e.z * e.z + e.w * e.w);
  }
  return d;
}

std::vector<glm::vec4> heatmap(std::span<const float> values, float maxValue) {
  if (!(maxValue > 0.0f)) {
    maxValue = 0.0f;
    for (float v : values) maxValue = std::max(maxValue, v);
  }
  std::vector<glm::vec4> out(values.size());
  for (size_t i = 0; i < values.size(); ++i)
    out[i] = ramp(maxValue > 0.0f ? values[i] / maxValue : 0.0f);
  return out;
}

std::vector<glm::vec4> heatmap(std::span<const uint32_t> values, float maxValue) {
  std::vector<float> f(values.begin(), values.end());
  return heatmap(std::span<const float>(f), maxValue);
}

std::vector<uint32_t> sumCounts(const std::vector<std::vector<uint32_t>>& perRank) {
  std::vector<uint32_t> sum(perRank.empty() ? 0 : perRank.front().size(), 0);
  for (const auto& counts : perRank) {
    if (counts.size() != sum.size())
      throw std::invalid_argument("fragment count heatmaps of different sizes");
    for (size_t i = 0; i < sum.size(); ++i) sum[i] += counts[i];
  }
  return sum;
}

}  // namespace sm::comp
