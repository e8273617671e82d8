#include "scene/control_points.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

namespace sm::scene {
namespace {

// Index of the first node with x >= the sample (the nodes with smaller x are behind it): VTK
// advances through the nodes while the sample lies past them.
template <class Node>
size_t nodeAtOrAfter(std::span<const Node> nodes, double x) {
  return size_t(std::lower_bound(nodes.begin(), nodes.end(), x,
                                 [](const Node& n, double v) { return n.x < v; }) -
                nodes.begin());
}

// The fraction in the interval [x1, x2], remapped by the left node's midpoint, and its sharpness.
struct Segment {
  double s, sharpness;
};

template <class Node>
Segment segmentAt(const Node& left, const Node& right, double x) {
  const double s = right.x != left.x ? (x - left.x) / (right.x - left.x) : 0.0;
  return {applyMidpoint(s, std::clamp(left.midpoint, 0.00001, 0.99999)), left.sharpness};
}

// The fraction bent towards the ends by sharpness in [0.01, 0.99].
double bend(double s, double sharpness) {
  if (s < 0.5) return 0.5 * std::pow(s * 2, 1.0 + 10 * sharpness);
  if (s > 0.5) return 1.0 - 0.5 * std::pow((1.0 - s) * 2, 1.0 + 10 * sharpness);
  return s;
}

// Hermite weights at a bent fraction.
struct Hermite {
  double h1, h2, h34;  // weights of y1, y2 and of the (shared) end slope
};

Hermite hermite(double s) {
  const double ss = s * s, sss = ss * s;
  return {2 * sss - 3 * ss + 1, -2 * sss + 3 * ss, (sss - 2 * ss + s) + (sss - ss)};
}

template <class T>
T hermiteValue(const Hermite& w, const T& y1, const T& y2, double sharpness) {
  return w.h1 * y1 + w.h2 * y2 + w.h34 * ((1.0 - sharpness) * (y2 - y1));
}

}  // namespace

double applyMidpoint(double s, double midpoint) {
  return s < midpoint ? 0.5 * s / midpoint : 0.5 + 0.5 * (s - midpoint) / (1.0 - midpoint);
}

double evaluateOpacity(std::span<const OpacityNode> nodes, double x) {
  if (nodes.empty()) return 0.0;
  const size_t i = nodeAtOrAfter(nodes, x);
  if (i >= nodes.size()) return nodes.back().y;
  if (i == 0) return nodes.front().y;
  const OpacityNode &a = nodes[i - 1], &b = nodes[i];
  Segment seg = segmentAt(a, b, x);
  if (seg.sharpness > 0.99) return seg.s < 0.5 ? a.y : b.y;
  if (seg.sharpness < 0.01) return (1 - seg.s) * a.y + seg.s * b.y;
  const double y = hermiteValue(hermite(bend(seg.s, seg.sharpness)), a.y, b.y, seg.sharpness);
  return std::clamp(y, std::min(a.y, b.y), std::max(a.y, b.y));
}

glm::dvec3 evaluateColor(std::span<const ColorNode> nodes, double x, ColorSpace space,
                         bool hsvWrap) {
  if (nodes.empty()) return glm::dvec3(0.0);
  const size_t i = nodeAtOrAfter(nodes, x);
  if (i >= nodes.size()) return nodes.back().rgb;
  if (i == 0) return nodes.front().rgb;
  const ColorNode &a = nodes[i - 1], &b = nodes[i];
  Segment seg = segmentAt(a, b, x);
  if (seg.sharpness > 0.99) return seg.s < 0.5 ? a.rgb : b.rgb;
  if (seg.sharpness < 0.01) return interpolateColor(a.rgb, b.rgb, seg.s, space, hsvWrap);
  const double bent = bend(seg.s, seg.sharpness);
  const Hermite w = hermite(bent);
  glm::dvec3 c;
  switch (space) {
    case ColorSpace::Step:
      return b.rgb;
    // VTK has no Hermite curve in Msh: the bent fraction, interpolated as without sharpness.
    case ColorSpace::Diverging:
      c = interpolateColor(a.rgb, b.rgb, bent, space);
      break;
    case ColorSpace::HSV: {
      glm::dvec3 h1 = rgbToHsv(a.rgb), h2 = rgbToHsv(b.rgb);
      if (hsvWrap && std::abs(h1.x - h2.x) > 0.5) (h1.x > h2.x ? h1.x : h2.x) -= 1.0;
      glm::dvec3 h = hermiteValue(w, h1, h2, seg.sharpness);
      if (h.x < 0.0) h.x += 1.0;
      c = hsvToRgb(h);
      break;
    }
    default:  // RGB, Lab, Prolab: the curve through each component in the space
      c = fromSpace(hermiteValue(w, toSpace(a.rgb, space), toSpace(b.rgb, space), seg.sharpness),
                    space);
  }
  return glm::clamp(c, 0.0, 1.0);
}

}  // namespace sm::scene
