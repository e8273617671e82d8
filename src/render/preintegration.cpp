#include "render/preintegration.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "common/parallel.h"

namespace sm::render {
namespace {
// Cumulative extinction at four points per transfer-function cell: the function is piecewise
// quadratic there, so linear interpolation between these points is accurate to ~1e-5.
int cumulativeBinsFor(const scene::TransferFunction& tf) {
  return int(tf.table.size() - 1) * 4 + 1;
}

// x rounded to float, as the device will hold it. Through a volatile: GCC 12.2 at -O3 vectorises
// the pair double(float(lo)), double(float(hi)) into a conversion whose result it then drops,
// storing lo and hi unrounded (reproduced outside this code base), which put the tables' grid
// off the device's for a constant field of 1e7.
double asFloat(double x) {
  volatile float f = float(x);
  return f;
}
}  // namespace

double PreintegrationTable::coordinate(double s) const {
  if (!(hi > lo)) return 0.0;
  if (scale == scene::ScalarScale::Log)  // the shader's formula, in double
    return s > 0.0 ? std::clamp((std::log2(s) - std::log2(lo)) / (std::log2(hi) - std::log2(lo)),
                                0.0, 1.0)
                   : 0.0;
  return std::clamp((s - lo) / (hi - lo), 0.0, 1.0);
}

double PreintegrationTable::gridValue(int i, int n) const {
  if (scale == scene::ScalarScale::Log)
    return i <= 0 ? lo : i >= n - 1 ? hi : lo * std::pow(hi / lo, double(i) / (n - 1));
  return lo + (hi - lo) * i / (n - 1);
}

double PreintegrationTable::cumulativeAt(double s) const {
  const int n = int(cumulative.size());
  double x = coordinate(s) * (n - 1);
  int i = std::min(int(x), n - 2);
  return cumulative[i] + (cumulative[i + 1] - cumulative[i]) * (x - i);
}

double PreintegrationTable::sigmaAt(double s) const {
  const int n = int(sigma.size());
  double x = coordinate(s) * (n - 1);
  int i = std::min(int(x), n - 2);
  return sigma[i] + (sigma[i + 1] - sigma[i]) * (x - i);
}

glm::dvec3 PreintegrationTable::colorAt(double sf, double sb, double L) const {
  auto coord = [&](double s) { return coordinate(s) * (scalarBins - 1); };
  double x[3] = {coord(sf), coord(sb),
                 std::sqrt(std::clamp(L * sigmaMax / tauMax, 0.0, 1.0)) * (lengthBins - 1)};
  const int n[3] = {scalarBins, scalarBins, lengthBins};
  int l0[3], l1[3];
  double w[3];
  for (int a = 0; a < 3; ++a) {
    l0[a] = std::min(int(x[a]), n[a] - 1);
    l1[a] = std::min(l0[a] + 1, n[a] - 1);
    w[a] = x[a] - l0[a];
  }
  glm::dvec3 r(0.0);
  for (int c = 0; c < 8; ++c) {
    int f = c & 1 ? l1[0] : l0[0], b = c & 2 ? l1[1] : l0[1], l = c & 4 ? l1[2] : l0[2];
    double wt = (c & 1 ? w[0] : 1 - w[0]) * (c & 2 ? w[1] : 1 - w[1]) * (c & 4 ? w[2] : 1 - w[2]);
    r += wt * glm::dvec3(colors[(size_t(l) * scalarBins + b) * scalarBins + f]);
  }
  return r;
}

glm::dvec4 PreintegrationTable::integrateInside(double sf, double sb, double L) const {
  double ds = sb - sf;
  const double small =
      scale == scene::ScalarScale::Log ? std::max(sf, sb) * std::log(hi / lo) : hi - lo;
  double mean = std::abs(ds) > kSmallDelta * small ? (cumulativeAt(sb) - cumulativeAt(sf)) / ds
                                                   : sigmaAt(0.5 * (sf + sb));
  double alpha = 1.0 - std::exp(-L * std::max(mean, 0.0));
  return glm::dvec4(colorAt(sf, sb, L) * alpha, alpha);
}

glm::dvec4 PreintegrationTable::integrateConstant(glm::vec4 end, double L) {
  double alpha = 1.0 - std::exp(-L * double(end.a));
  return glm::dvec4(glm::dvec3(end) * alpha, alpha);
}

glm::dvec4 PreintegrationTable::integrate(double sf, double sb, double L) const {
  if (!(L > 0) || !std::isfinite(sf) || !std::isfinite(sb)) return glm::dvec4(0.0);
  // Three pieces: [0, c1] outside on sf's side, [c1, c2] inside [lo, hi], [c2, 1] outside on sb's
  // side; the shader does the same.
  double c1, c2;
  if (sb != sf) {
    double uLo = (lo - sf) / (sb - sf), uHi = (hi - sf) / (sb - sf);
    c1 = std::clamp(std::min(uLo, uHi), 0.0, 1.0);
    c2 = std::clamp(std::max(uLo, uHi), 0.0, 1.0);
  } else {
    c1 = sf >= lo && sf <= hi ? 0.0 : 1.0;
    c2 = 1.0;
  }
  glm::dvec4 acc(0.0);
  if (c1 > 0.0) acc = integrateConstant(sf < lo ? below : above, c1 * L);
  if (c2 > c1) {
    double a = std::clamp(sf + (sb - sf) * c1, lo, hi), b = std::clamp(sf + (sb - sf) * c2, lo, hi);
    acc += (1.0 - acc.a) * integrateInside(a, b, (c2 - c1) * L);
  }
  if (c2 < 1.0) acc += (1.0 - acc.a) * integrateConstant(sb < lo ? below : above, (1.0 - c2) * L);
  return acc;
}

uint64_t PreintegrationTable::encodeColor(glm::vec3 c) {
  constexpr double scale = double(uint64_t(1) << kColorBits);
  constexpr uint64_t top = (uint64_t(1) << kColorBits) - 1;
  uint64_t w = 0;
  for (int i = 0; i < 3; ++i) {
    double v = std::isfinite(c[i]) ? std::clamp(double(c[i]), 0.0, 1.0) : 0.0;
    w |= std::min(uint64_t(std::llround(v * scale)), top) << (kColorBits * i);
  }
  return w;
}

glm::vec3 PreintegrationTable::decodeColor(uint64_t w) {
  // float(code) * 2^-21 is exact, so this equals the shader's decoding bit for bit.
  constexpr uint64_t top = (uint64_t(1) << kColorBits) - 1;
  constexpr float step = 1.0f / float(uint64_t(1) << kColorBits);
  glm::vec3 c;
  for (int i = 0; i < 3; ++i) c[i] = float((w >> (kColorBits * i)) & top) * step;
  return c;
}

std::vector<uint64_t> PreintegrationTable::deviceWords() const {
  std::vector<uint64_t> w;
  w.reserve(colors.size() + cumulative.size() + 3);
  for (const glm::vec3& c : colors) w.push_back(encodeColor(c));
  auto pack = [](float lo, float hi) {
    return uint64_t(std::bit_cast<uint32_t>(lo)) | uint64_t(std::bit_cast<uint32_t>(hi)) << 32;
  };
  for (size_t i = 0; i + 1 < cumulative.size(); ++i)
    w.push_back(pack(cumulative[i], cumulative[i + 1]));
  for (glm::vec4 e : {below, above}) {
    w.push_back(pack(e.r, e.g));
    w.push_back(pack(e.b, e.a));
  }
  return w;
}

uint64_t preintegrationDeviceBytes(const scene::TransferFunction& tf, int scalarBins,
                                   int lengthBins) {
  const uint64_t colors = uint64_t(scalarBins) * scalarBins * lengthBins;
  const uint64_t pairs = uint64_t(cumulativeBinsFor(tf) - 1), ends = 4;
  return (colors + pairs + ends) * sizeof(uint64_t);
}

PreintegrationTable buildPreintegration(const scene::TransferFunction& tf, int scalarBins,
                                        int lengthBins, double tauMax, int quadrature) {
  PreintegrationTable t;
  t.scalarBins = scalarBins;
  t.lengthBins = lengthBins;
  t.tauMax = tauMax;
  // The device computes table coordinates from float(lo) and float(hi): the grid is built on those
  // very values, or far from zero (101325 +- 1, say) the two would place the bins apart. A range
  // that float cannot tell from a point (a constant field: every value maps to the table's middle,
  // scene::TransferFunction::lookup) is widened around it: any interval reproduces a constant
  // function, and one with distinct float ends keeps the device's division finite.
  t.lo = asFloat(tf.lo);
  t.hi = asFloat(tf.hi);
  t.scale = tf.scale;
  const bool point = !(t.hi > t.lo);
  if (point && t.scale == scene::ScalarScale::Log) {  // widened by a factor: it stays positive
    const double mid = t.lo;
    t.lo = asFloat(mid * (1.0 - 0x1p-10));
    t.hi = asFloat(mid * (1.0 + 0x1p-10));
  } else if (point) {
    const double mid = t.lo, half = std::max(0.5, std::abs(mid) * 0x1p-16);
    t.lo = asFloat(mid - half);
    t.hi = asFloat(mid + half);
  }
  auto sigma = [&](double s) { return tf.lookup(s).a * tf.opacityScale / tf.unitDistance; };
  for (const auto& e : tf.table) {
    t.sigma.push_back(float(double(e.a) * tf.opacityScale / tf.unitDistance));
    t.sigmaMax = std::max(t.sigmaMax, double(t.sigma.back()));
  }
  if (point) t.sigma.assign(2, float(sigma(tf.lo)));
  // S over the range by Simpson's rule on each sub-interval (exact for the piecewise-linear sigma
  // of a linear scale; on a log one, sigma is linear in log s there, and the intervals are too
  // narrow for that to matter: a ratio of (hi / lo)^(1 / 1020)).
  const int nc = cumulativeBinsFor(tf);
  t.cumulative.assign(nc, 0.0f);
  double acc = 0.0;
  for (int i = 1; i < nc; ++i) {
    double a = t.gridValue(i - 1, nc), b = t.gridValue(i, nc);
    acc += (b - a) / 6.0 * (sigma(a) + 4 * sigma(0.5 * (a + b)) + sigma(b));
    t.cumulative[i] = float(acc);
  }
  auto end = [&](double s) { return glm::vec4(glm::vec3(tf.lookup(s)), float(sigma(s))); };
  t.below = end(t.lo);
  t.above = end(t.hi);
  t.colors.assign(size_t(scalarBins) * scalarBins * lengthBins, glm::vec3(0.0f));
  if (!(t.sigmaMax > 0)) return t;
  std::vector<double> lengths(lengthBins);
  for (int l = 0; l < lengthBins; ++l) {
    double x = double(l) / (lengthBins - 1);
    lengths[l] = x * x * tauMax / t.sigmaMax;
  }
  // lengths[l] = l^2 lengths[1], so exp(-lengths[l] cum) = g^(l^2) with g = exp(-lengths[1] cum):
  // one exponential per quadrature point, and two products per length bin (g^((l+1)^2) =
  // g^(l^2) g^(2l+1)), instead of an exponential per point and bin, which took 0.4 s of a first
  // image's CPU time on two cores. The products' rounding (a few ulps after 32 bins) is far below
  // the colours' 21 bits.
  parallelFor(int64_t(scalarBins) * scalarBins, [&](int64_t begin, int64_t end) {
    std::vector<double> sig(quadrature), cum(quadrature), power(quadrature), step(quadrature),
        g2(quadrature);
    std::vector<glm::dvec3> col(quadrature);
    for (int64_t pair = begin; pair < end; ++pair) {
      const int f = int(pair % scalarBins), b = int(pair / scalarBins);
      const double sf = t.gridValue(f, scalarBins), sb = t.gridValue(b, scalarBins);
      const double du = 1.0 / quadrature;
      double running = 0.0;
      for (int q = 0; q < quadrature; ++q) {  // midpoint rule in u
        glm::dvec4 v = tf.lookup(sf + (sb - sf) * (q + 0.5) * du);
        sig[q] = v.a * tf.opacityScale / tf.unitDistance;
        col[q] = glm::dvec3(v);
        cum[q] = running + 0.5 * sig[q] * du;
        running += sig[q] * du;
      }
      for (int q = 0; q < quadrature; ++q) {
        power[q] = 1.0;                                                   // g^(l^2), l = 0
        step[q] = lengthBins > 1 ? std::exp(-lengths[1] * cum[q]) : 1.0;  // g^(2l+1)
        g2[q] = step[q] * step[q];
      }
      for (int l = 0; l < lengthBins; ++l) {
        // Weights of the colours: extinction times transmittance up to there. Their normalised sum
        // is the mean colour N; at L = 0 it is the extinction-weighted mean.
        glm::dvec3 c(0.0);
        double weight = 0.0;
        for (int q = 0; q < quadrature; ++q) {
          double w = sig[q] * power[q];
          c += w * col[q];
          weight += w;
          power[q] *= step[q];
          step[q] *= g2[q];
        }
        glm::dvec3 mean = weight > 0 ? c / weight : col[quadrature / 2];
        t.colors[(size_t(l) * scalarBins + b) * scalarBins + f] =
            PreintegrationTable::decodeColor(PreintegrationTable::encodeColor(glm::vec3(mean)));
      }
    }
  });
  return t;
}

}  // namespace sm::render
