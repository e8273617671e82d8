// Images for the paper's comparison figures, as float RGBA that callers write out (the compositor
// knows no file formats): the per-pixel L2 difference between two composited images (deep versus
// single-fragment compositing), and heatmaps of scalar fields such as per-rank fragment counts.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

namespace sm::comp {

// Per pixel: the Euclidean distance between the two premultiplied RGBA values.
std::vector<float> l2Difference(std::span<const glm::vec4> a, std::span<const glm::vec4> b);

// Maps values to colours (black, purple, orange, yellow: a perceptually ordered ramp like
// "inferno"), 0 to black and `maxValue` (or above) to yellow; opaque. maxValue <= 0: the largest
// value.
std::vector<glm::vec4> heatmap(std::span<const float> values, float maxValue = 0.0f);
std::vector<glm::vec4> heatmap(std::span<const uint32_t> values, float maxValue = 0.0f);

// Per-pixel sum of several ranks' fragment counts (the paper's combined heatmap).
std::vector<uint32_t> sumCounts(const std::vector<std::vector<uint32_t>>& perRank);

}  // namespace sm::comp
