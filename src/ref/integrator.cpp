#include "ref/integrator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/common.hpp>

#include "common/check.h"

namespace sm::ref {

namespace {

constexpr int kMinDepth = 2;   // every piece is bisected at least this often
constexpr int kMaxDepth = 20;  // bisection limit (a piece of 2^-20 of its crossing)
constexpr int kMaxInitialPieces = 1024;
constexpr double kCellsPerPiece = 4.0;

// The smallest k >= 0 with k * dt >= tIn, as the product is evaluated (not as tIn / dt rounds).
int64_t firstSample(double tIn, double dt) {
  if (!(tIn > 0.0)) return 0;
  double q = std::ceil(tIn / dt);
  int64_t k = q < 4e18 ? int64_t(q) : int64_t(4e18);
  while (k > 0 && double(k - 1) * dt >= tIn) --k;
  while (double(k) * dt < tIn) ++k;
  return k;
}

double tfCoordinate(const scene::TransferFunction& tf, double s) {
  if (!(tf.hi > tf.lo)) return 0.5;
  if (tf.scale == scene::ScalarScale::Log) {
    if (!(s > 0.0)) return 0.0;
    return std::clamp((std::log10(s) - std::log10(tf.lo)) / std::log10(tf.hi / tf.lo), 0.0, 1.0);
  }
  return std::clamp((s - tf.lo) / (tf.hi - tf.lo), 0.0, 1.0);
}

}  // namespace

RayIntegrator::RayIntegrator(const ReferenceRenderer& renderer, const glm::dvec3& origin,
                             const glm::dvec3& dir, std::span<const float> values,
                             const scene::TransferFunction& tf, const RenderSettings& settings)
    : renderer_(renderer),
      origin_(origin),
      dir_(dir),
      values_(values),
      tf_(tf),
      settings_(settings) {}

void RayIntegrator::integrate(std::span<const Crossing> crossings, Accumulator& acc,
                              PixelStats& stats) const {
  std::vector<Crossing> clipped;
  if (!settings_.clipPlanes.empty()) {
    const scene::ClipSpan span = scene::clipSpan(settings_.clipPlanes, origin_, dir_);
    for (Crossing c : crossings) {
      c.tIn = std::max(c.tIn, span.lo);
      c.tOut = std::min(c.tOut, span.hi);
      if (c.tOut > c.tIn) clipped.push_back(c);
    }
    crossings = clipped;
  }
  if (settings_.mode == RenderMode::Grid) {
    grid(crossings, acc, stats);
  } else {
    converged(crossings, acc, stats);
  }
}

RayIntegrator::Medium RayIntegrator::mediumAt(const Crossing& c, double t,
                                              PixelStats& stats) const {
  ++stats.samples;
  double s = renderer_.scalar(c.type, c.index, values_, origin_ + t * dir_);
  return {glm::dvec3(tf_.lookup(s)), tf_.extinction(s)};
}

void RayIntegrator::grid(std::span<const Crossing> crossings, Accumulator& acc,
                         PixelStats& stats) const {
  const double dt = settings_.dt, threshold = settings_.earlyTermination;
  int64_t next = 0;  // samples below this were taken by an earlier crossing
  for (const Crossing& c : crossings) {
    if (acc.alpha >= threshold) return;
    int64_t k = std::max(next, firstSample(c.tIn, dt));
    for (; double(k) * dt < c.tOut; ++k) {
      Medium m = mediumAt(c, double(k) * dt, stats);
      double a = -std::expm1(-m.sigma * dt);  // 1 - exp(-sigma dt), without cancellation
      acc.under(a * m.rgb, a);
      if (acc.alpha >= threshold) return;
    }
    next = std::max(next, k);
  }
}

void RayIntegrator::converged(std::span<const Crossing> crossings, Accumulator& acc,
                              PixelStats& stats) const {
  // Each point of the ray is integrated once, in the first crossing that covers it.
  double total = 0.0, covered = -std::numeric_limits<double>::infinity();
  for (const Crossing& c : crossings) {
    total += std::max(0.0, c.tOut - std::max(c.tIn, covered));
    covered = std::max(covered, c.tOut);
  }
  covered = -std::numeric_limits<double>::infinity();
  for (const Crossing& c : crossings) {
    const double a = std::max(c.tIn, covered), b = c.tOut;
    covered = std::max(covered, b);
    if (!(b > a)) continue;
    const int n = initialPieces(c, a, b, stats);
    for (int i = 0; i < n; ++i) {
      if (acc.alpha >= settings_.earlyTermination) return;
      double pa = a + (b - a) * i / n, pb = i + 1 == n ? b : a + (b - a) * (i + 1) / n;
      double tol = settings_.tolerance * (pb - pa) / total;
      Piece p = adaptive(c, pa, pb, midpoint(c, pa, pb, stats), tol, 0, stats);
      acc.under(p.color, p.alpha);
    }
  }
}

// One piece per kCellsPerPiece transfer-function cells that the scalar spans (estimated from
// three samples): with the two compulsory bisections, every table cell then gets a sample, so a
// one-entry spike in the table cannot fall between samples and go unnoticed.
int RayIntegrator::initialPieces(const Crossing& c, double a, double b, PixelStats& stats) const {
  double lo = 1.0, hi = 0.0;
  for (int j = 0; j < 3; ++j) {
    ++stats.samples;
    double s = renderer_.scalar(c.type, c.index, values_, origin_ + (a + (b - a) * j / 2) * dir_);
    if (!std::isfinite(s)) continue;
    double x = tfCoordinate(tf_, s);
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  if (hi < lo || tf_.table.size() < 2) return 1;
  double pieces = std::ceil((hi - lo) * double(tf_.table.size() - 1) / kCellsPerPiece);
  return int(std::clamp(pieces, 1.0, double(kMaxInitialPieces)));
}

RayIntegrator::Piece RayIntegrator::midpoint(const Crossing& c, double a, double b,
                                             PixelStats& stats) const {
  Medium m = mediumAt(c, 0.5 * (a + b), stats);
  double alpha = -std::expm1(-m.sigma * (b - a));  // exact attenuation for constant sigma
  return {alpha * m.rgb, alpha};
}

RayIntegrator::Piece RayIntegrator::adaptive(const Crossing& c, double a, double b,
                                             const Piece& whole, double tol, int depth,
                                             PixelStats& stats) const {
  auto over = [](const Piece& f, const Piece& g) {
    return Piece{f.color + (1.0 - f.alpha) * g.color, f.alpha + (1.0 - f.alpha) * g.alpha};
  };
  const double m = 0.5 * (a + b);
  Piece left = midpoint(c, a, m, stats), right = midpoint(c, m, b, stats);
  Piece both = over(left, right);
  glm::dvec3 dc = glm::abs(both.color - whole.color);
  double err = std::max({dc.x, dc.y, dc.z, std::abs(both.alpha - whole.alpha)});
  if (depth + 1 >= kMinDepth && !(err > tol)) return both;
  if (depth + 1 >= kMaxDepth || !(m > a && b > m)) {
    ++stats.unconverged;
    return both;
  }
  return over(adaptive(c, a, m, left, 0.5 * tol, depth + 1, stats),
              adaptive(c, m, b, right, 0.5 * tol, depth + 1, stats));
}

}  // namespace sm::ref
