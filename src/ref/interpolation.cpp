#include "ref/interpolation.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <initializer_list>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "common/check.h"

namespace sm::ref {

using mesh::CellType;

namespace {

// Hexahedron vertex i sits at r = kHexR[i], s = kHexS[i], t = kHexT[i] (VTK order).
constexpr int kHexR[8] = {0, 1, 1, 0, 0, 1, 1, 0};
constexpr int kHexS[8] = {0, 0, 1, 1, 0, 0, 1, 1};
constexpr int kHexT[8] = {0, 0, 0, 0, 1, 1, 1, 1};

constexpr double kStepTolerance = 1e-10;
constexpr double kResidualTolerance = 1e-14;  // relative to the element's size
constexpr int kMaxSteps = 40;
constexpr int kMaxHalvings = 10;

void hexShape(const glm::dvec3& p, double* n, double* dr, double* ds, double* dt) {
  for (int i = 0; i < 8; ++i) {
    double fr = kHexR[i] ? p.x : 1 - p.x, gr = kHexR[i] ? 1 : -1;
    double fs = kHexS[i] ? p.y : 1 - p.y, gs = kHexS[i] ? 1 : -1;
    double ft = kHexT[i] ? p.z : 1 - p.z, gt = kHexT[i] ? 1 : -1;
    if (n) n[i] = fr * fs * ft;
    if (dr) {
      dr[i] = gr * fs * ft;
      ds[i] = fr * gs * ft;
      dt[i] = fr * fs * gt;
    }
  }
}

void set(double* a, std::initializer_list<double> v) {
  std::copy(v.begin(), v.end(), a);
}

glm::dvec3 solve3(const glm::dvec3& c0, const glm::dvec3& c1, const glm::dvec3& c2,
                  const glm::dvec3& rhs, double& det) {
  glm::dvec3 c12 = glm::cross(c1, c2);
  det = glm::dot(c0, c12);
  return glm::dvec3(glm::dot(rhs, c12), glm::dot(c0, glm::cross(rhs, c2)),
                    glm::dot(c0, glm::cross(c1, rhs))) /
         det;
}

double maxAbs(const glm::dvec3& v) {
  return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

double elementSize(std::span<const glm::dvec3> corners) {
  double size = 0.0;
  for (const auto& c : corners) size = std::max(size, glm::length(c - corners[0]));
  return size;
}

// Euclidean projection onto {x >= 0, sum x <= 1} (n = 2 or 3): clamp the negatives, and if the
// sum still exceeds 1, project onto the face sum x = 1 (Held, Wolfe and Crowder's sort method).
void projectToSimplex(double* x, int n) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += std::max(x[i], 0.0);
  if (sum <= 1.0) {
    for (int i = 0; i < n; ++i) x[i] = std::max(x[i], 0.0);
    return;
  }
  double u[3] = {x[0], x[1], n > 2 ? x[2] : 0.0};
  std::sort(u, u + n, std::greater<>());
  double prefix = 0.0, theta = 0.0;
  for (int j = 0; j < n; ++j) {
    prefix += u[j];
    double candidate = (prefix - 1.0) / (j + 1);
    if (u[j] - candidate > 0.0) theta = candidate;
  }
  for (int i = 0; i < n; ++i) x[i] = std::max(x[i] - theta, 0.0);
}

Inversion invertTet(std::span<const glm::dvec3> c, const glm::dvec3& p) {
  Inversion inv;
  double det = 0.0;
  inv.rst = solve3(c[1] - c[0], c[2] - c[0], c[3] - c[0], p - c[0], det);
  inv.iterations = 1;
  inv.converged = std::abs(det) > 0.0 && std::isfinite(maxAbs(inv.rst));
  if (!inv.converged) inv.rst = parametricCenter(CellType::Tet);  // flat: no better answer
  inv.residual = glm::length(parametricToWorld(CellType::Tet, c, inv.rst) - p);
  return inv;
}

// One Newton run from `start`; updates `best` whenever an iterate has a smaller residual.
void newtonFrom(CellType type, std::span<const glm::dvec3> c, const glm::dvec3& p,
                const glm::dvec3& start, double scale, Inversion& best) {
  const uint32_t nv = mesh::numVerts(type);
  double dr[kMaxElementVerts], ds[kMaxElementVerts], dt[kMaxElementVerts];
  glm::dvec3 x = start, res = parametricToWorld(type, c, x) - p;
  double rn = glm::length(res);
  auto record = [&](bool converged) {
    if (rn <= best.residual || converged) {
      best.rst = x;
      best.residual = rn;
      best.converged = converged;
    }
  };
  record(rn <= kResidualTolerance * scale);
  if (best.converged) return;
  for (int step = 0; step < kMaxSteps; ++step) {
    shapeDerivatives(type, x, dr, ds, dt);
    glm::dvec3 jr(0.0), js(0.0), jt(0.0);
    for (uint32_t i = 0; i < nv; ++i) {
      jr += dr[i] * c[i];
      js += ds[i] * c[i];
      jt += dt[i] * c[i];
    }
    double det = 0.0;
    glm::dvec3 delta = solve3(jr, js, jt, -res, det);
    if (!(std::abs(det) > 0.0) || !std::isfinite(maxAbs(delta))) return;  // singular Jacobian
    ++best.iterations;
    glm::dvec3 xn = x;
    double rnn = rn;
    bool accepted = false;
    for (int h = 0; h <= kMaxHalvings && !accepted; ++h, delta *= 0.5) {
      xn = glm::clamp(x + delta, glm::dvec3(-1.0), glm::dvec3(2.0));
      rnn = glm::length(parametricToWorld(type, c, xn) - p);
      accepted = rnn < rn || maxAbs(delta) <= kStepTolerance;
    }
    if (!accepted) return;  // no descent along the Newton direction: stalled
    double moved = maxAbs(xn - x);
    x = xn;
    rn = rnn;
    res = parametricToWorld(type, c, x) - p;
    bool converged = moved <= kStepTolerance || rn <= kResidualTolerance * scale;
    record(converged);
    if (converged) return;
  }
}

}  // namespace

void shapeFunctions(CellType type, const glm::dvec3& q, double* n) {
  const double r = q.x, s = q.y, t = q.z;
  switch (type) {
    case CellType::Tet:
      set(n, {1 - r - s - t, r, s, t});
      return;
    case CellType::Pyramid:
      set(n, {(1 - r) * (1 - s) * (1 - t), r * (1 - s) * (1 - t), r * s * (1 - t),
              (1 - r) * s * (1 - t), t});
      return;
    case CellType::Wedge:
      set(n, {(1 - r - s) * (1 - t), r * (1 - t), s * (1 - t), (1 - r - s) * t, r * t, s * t});
      return;
    case CellType::Hex:
      hexShape(q, n, nullptr, nullptr, nullptr);
      return;
  }
}

void shapeDerivatives(CellType type, const glm::dvec3& q, double* dr, double* ds, double* dt) {
  const double r = q.x, s = q.y, t = q.z;
  switch (type) {
    case CellType::Tet:
      set(dr, {-1, 1, 0, 0});
      set(ds, {-1, 0, 1, 0});
      set(dt, {-1, 0, 0, 1});
      return;
    case CellType::Pyramid:
      set(dr, {-(1 - s) * (1 - t), (1 - s) * (1 - t), s * (1 - t), -s * (1 - t), 0});
      set(ds, {-(1 - r) * (1 - t), -r * (1 - t), r * (1 - t), (1 - r) * (1 - t), 0});
      set(dt, {-(1 - r) * (1 - s), -r * (1 - s), -r * s, -(1 - r) * s, 1});
      return;
    case CellType::Wedge:
      set(dr, {-(1 - t), 1 - t, 0, -t, t, 0});
      set(ds, {-(1 - t), 0, 1 - t, -t, 0, t});
      set(dt, {-(1 - r - s), -r, -s, 1 - r - s, r, s});
      return;
    case CellType::Hex:
      hexShape(q, nullptr, dr, ds, dt);
      return;
  }
}

glm::dvec3 parametricToWorld(CellType type, std::span<const glm::dvec3> corners,
                             const glm::dvec3& rst) {
  double n[kMaxElementVerts];
  shapeFunctions(type, rst, n);
  glm::dvec3 x(0.0);
  for (uint32_t i = 0; i < mesh::numVerts(type); ++i) x += n[i] * corners[i];
  return x;
}

glm::dvec3 parametricCenter(CellType type) {
  switch (type) {
    case CellType::Tet:
      return glm::dvec3(0.25);
    case CellType::Pyramid:
      return {0.5, 0.5, 0.2};  // the centroid of the reference pyramid
    case CellType::Wedge:
      return {1.0 / 3.0, 1.0 / 3.0, 0.5};
    case CellType::Hex:
      return glm::dvec3(0.5);
  }
  return glm::dvec3(0.0);
}

glm::dvec3 parametricVertex(CellType type, uint32_t v) {
  switch (type) {
    case CellType::Tet:
      return glm::dvec3(v == 1, v == 2, v == 3);
    case CellType::Pyramid:
      return v == 4 ? glm::dvec3(0.5, 0.5, 1) : glm::dvec3(kHexR[v], kHexS[v], 0);
    case CellType::Wedge:
      return glm::dvec3(v % 3 == 1, v % 3 == 2, v >= 3);
    case CellType::Hex:
      return glm::dvec3(kHexR[v], kHexS[v], kHexT[v]);
  }
  return glm::dvec3(0.0);
}

glm::dvec3 clampToDomain(CellType type, const glm::dvec3& rst) {
  glm::dvec3 q = glm::clamp(rst, glm::dvec3(0.0), glm::dvec3(1.0));
  if (type == CellType::Tet) {
    q = rst;
    projectToSimplex(glm::value_ptr(q), 3);
  } else if (type == CellType::Wedge) {
    q.z = std::clamp(rst.z, 0.0, 1.0);
    q.x = rst.x;
    q.y = rst.y;
    projectToSimplex(glm::value_ptr(q), 2);
  }
  return q;
}

Inversion worldToParametric(CellType type, std::span<const glm::dvec3> corners,
                            const glm::dvec3& p) {
  const uint32_t nv = mesh::numVerts(type);
  SM_DCHECK(corners.size() >= nv);
  // Relative to a corner, so that residuals keep their precision far from the origin.
  glm::dvec3 local[kMaxElementVerts];
  for (uint32_t i = 0; i < nv; ++i) local[i] = corners[i] - corners[0];
  const std::span<const glm::dvec3> c(local, nv);
  const glm::dvec3 q = p - corners[0];
  if (type == CellType::Tet) return invertTet(c, q);
  const double scale = elementSize(c);
  Inversion best;
  best.residual = INFINITY;
  newtonFrom(type, c, q, parametricCenter(type), scale, best);
  // Fallback for strongly distorted elements: start near each vertex in turn.
  for (uint32_t v = 0; v < nv && !best.converged; ++v) {
    glm::dvec3 center = parametricCenter(type);
    newtonFrom(type, c, q, center + 0.75 * (parametricVertex(type, v) - center), scale, best);
  }
  if (!std::isfinite(best.residual)) best.rst = parametricCenter(type);
  return best;
}

double interpolate(CellType type, std::span<const glm::dvec3> corners,
                   std::span<const double> values, const glm::dvec3& p) {
  double n[kMaxElementVerts];
  shapeFunctions(type, clampToDomain(type, worldToParametric(type, corners, p).rst), n);
  double s = 0.0;
  for (uint32_t i = 0; i < mesh::numVerts(type); ++i) s += n[i] * values[i];
  return s;
}

}  // namespace sm::ref
