// Analytic point fields. Coordinates are first mapped to the unit cube of the mesh bounds, so the
// same features (a shock front, a vortex core) cross every mesh whatever its size or position.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "common/error.h"
#include "common/parallel.h"
#include "gen/generate.h"

namespace sm::gen {
namespace {

constexpr double kPi = std::numbers::pi;

// x + 2y + 3z scaled to [0, 1]: affine in the coordinates, so every linear or multilinear
// element interpolates it exactly and differently split meshes of one domain render the same.
double linearField(const glm::dvec3& u) {
  return (u.x + 2.0 * u.y + 3.0 * u.z) / 6.0;
}

// A planar shock (density-like jump from 1 to 4) smoothed over a few percent of the domain,
// sweeping the domain as t goes from 0 to 1, with a gentle ripple behind it.
double shockField(const glm::dvec3& u, double t) {
  const glm::dvec3 normal = glm::normalize(glm::dvec3(1.0, 0.35, 0.2));
  const double front = 0.15 + 0.8 * t;
  const double s = glm::dot(u - glm::dvec3(0.0, 0.5, 0.5), normal);
  const double behind = 0.5 * (1.0 + std::tanh((front - s) / 0.025));
  const double ripple = 0.15 * std::sin(6.0 * kPi * s) * std::sin(2.0 * kPi * u.y);
  return 1.0 + behind * (3.0 + ripple);
}

// Speed of a Lamb-Oseen vortex (peak 1 at r ~ 1.12 rc) whose core axis runs along z, wobbles
// with height and drifts across the domain over time.
double vortexField(const glm::dvec3& u, double t) {
  const double phase = 2.0 * kPi * (u.z + t);
  const glm::dvec2 centre(0.3 + 0.4 * t + 0.08 * std::cos(phase), 0.5 + 0.08 * std::sin(phase));
  const double rc = 0.12, peak = 0.6381727;  // max of (1 - exp(-q^2)) / q, at q = 1.1209
  const double r = glm::length(glm::dvec2(u.x, u.y) - centre);
  const double q = r / rc;
  // (1 - exp(-q^2)) / q, written to stay accurate (and finite) at the axis.
  const double profile = q < 1e-4 ? q : -std::expm1(-q * q) / q;
  return profile / peak;
}

// Density around a blunt body of unit radius at the origin facing -x in a hypersonic stream along
// +x (the capsule and lander; in world units, not normalised): a paraboloidal bow shock standing
// off the nose, whose jump weakens from the strong-shock 5.5 on the axis to 1 as it turns oblique,
// a shock layer compressing further towards the nose, and a low-density wake that sways with time.
double densityField(const glm::dvec3& p, double t) {
  const double r2 = p.y * p.y + p.z * p.z, shockRadius = 1.7;
  const double standoff = -0.45 - 0.05 * std::sin(2.0 * kPi * t);
  const double xs = standoff + r2 / (2.0 * shockRadius);  // the shock surface
  const double jump = 4.5 / (1.0 + r2 / (shockRadius * shockRadius));
  const double behind = 0.5 * (1.0 + std::tanh((p.x - xs) / 0.06));
  const double layer = 0.8 * std::exp(-(p.x - standoff) * (p.x - standoff) / 0.5 - r2 / 1.5);
  const double x = std::max(p.x - 1.2, 0.0);
  const double sway = 0.35 * std::sin(2.0 * kPi * (t - x / 6.0)) * std::min(x / 3.0, 1.0);
  const double wr2 = (p.y - sway) * (p.y - sway) + p.z * p.z, width = 0.8 + 0.12 * x;
  const double wake = p.x > 0.6 ? 0.75 * std::exp(-wr2 / (width * width) - x / 12.0) : 0.0;
  return 1.0 + behind * (jump + layer) * (1.0 - 0.8 * (p.x > 0.6 ? std::exp(-wr2) : 0.0)) - wake;
}

void setField(mesh::UnstructuredMesh& mesh, const std::string& name,
              std::vector<std::vector<float>> steps) {
  auto it = std::find_if(mesh.fields.begin(), mesh.fields.end(),
                         [&](const mesh::Field& f) { return f.name == name; });
  if (it == mesh.fields.end()) {
    mesh.fields.push_back(mesh::Field{name, std::move(steps)});
  } else {
    it->steps = std::move(steps);
  }
}

}  // namespace

void addAnalyticFields(mesh::UnstructuredMesh& mesh, int steps) {
  addAnalyticFields(mesh, steps, mesh.bounds());
}

void addAnalyticFields(mesh::UnstructuredMesh& mesh, int steps, const mesh::Bounds& b,
                       unsigned threads) {
  if (steps < 1) throw Error("the number of time steps must be at least 1, got ", steps);
  const glm::dvec3 lo = b.lo, extent = glm::max(b.extent(), glm::dvec3(1e-300));
  const size_t n = mesh.points.size();
  std::vector<std::vector<float>> linear(steps), shock(steps), vortex(steps), density(steps);
  mesh.timeValues.assign(steps, 0.0);
  for (int s = 0; s < steps; ++s) {
    const double t = steps == 1 ? 0.0 : double(s) / double(steps - 1);
    mesh.timeValues[s] = t;
    linear[s].resize(n);
    shock[s].resize(n);
    vortex[s].resize(n);
    density[s].resize(n);
    parallelFor(
        int64_t(n),
        [&](int64_t begin, int64_t end) {
          for (int64_t i = begin; i < end; ++i) {
            const glm::dvec3 u = (mesh.points[i] - lo) / extent;
            linear[s][i] = float(linearField(u));
            shock[s][i] = float(shockField(u, t));
            vortex[s][i] = float(vortexField(u, t));
            density[s][i] = float(densityField(mesh.points[i], t));
          }
        },
        threads);
  }
  setField(mesh, "linear", std::move(linear));
  setField(mesh, "shock", std::move(shock));
  setField(mesh, "vortex", std::move(vortex));
  setField(mesh, "density", std::move(density));
}

}  // namespace sm::gen
