// Body shapes. Both are revolved profiles (OpenCASCADE keeps the seam and the poles clean); the
// lander adds nozzles and legs by boolean union. Dimensions follow the flight vehicles loosely: an
// Apollo/Orion-like capsule (spherical heat shield of radius 1.2 D, 32.5 degree afterbody cone) and
// a lander: a blunt body with three canted retro-propulsion nozzles on its heat shield (as in
// NASA's FUN3D Mars lander runs) and three landing legs with foot pads on its base.
#include "gen/cfd_bodies.h"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vector_relational.hpp>

#include "common/check.h"

namespace sm::gen {
namespace {

namespace occ = gmsh::model::occ;
constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Size law constants, in body units at scale 1 (about 100 thousand elements).
constexpr double kWallSize = 0.08;       // on the body
constexpr double kGrowth = 0.3;          // size increase per unit distance from the body
constexpr double kMaxSize = 1.2;         // far field
constexpr double kWakeGrowth = 0.06;     // along the wake
constexpr double kHexSize = 0.14;        // hexahedral block
constexpr double kFeatureReach = 0.15;   // distance within which a part's floor applies
constexpr double kLayerFraction = 0.25;  // boundary-layer thickness / wall size

// A closed profile in the (x, r) half plane (z = 0, y = r), revolved about the x axis.
class Profile {
 public:
  Profile(double x, double r) : first_(occ::addPoint(x, r, 0)), last_(first_) {}
  void lineTo(double x, double r) {
    int p = occ::addPoint(x, r, 0);
    curves_.push_back(occ::addLine(last_, p));
    last_ = p;
  }
  void arcTo(double x, double r, double cx, double cr) {
    int c = occ::addPoint(cx, cr, 0), p = occ::addPoint(x, r, 0);
    curves_.push_back(occ::addCircleArc(last_, c, p));
    last_ = p;
  }
  int revolve() {
    curves_.push_back(occ::addLine(last_, first_));
    int face = occ::addPlaneSurface({occ::addCurveLoop(curves_)});
    gmsh::vectorpair out;
    occ::revolve({{2, face}}, 0, 0, 0, 1, 0, 0, 2 * kPi, out);
    for (const auto& [dim, tag] : out)
      if (dim == 3) return tag;
    SM_CHECK_MSG(false, "revolving the body profile gave no volume");
    return -1;
  }

 private:
  int first_, last_;
  std::vector<int> curves_;
};

// Surfaces of `volume` lying within x in [x0, x1] and radius `r` of the axis (to recombine).
std::vector<int> surfacesInBand(int volume, double x0, double x1, double r) {
  gmsh::vectorpair boundary;
  gmsh::model::getBoundary({{3, volume}}, boundary, false, false, false);
  std::vector<int> band;
  for (const auto& [dim, tag] : boundary) {
    double bx0, by0, bz0, bx1, by1, bz1;
    gmsh::model::getBoundingBox(dim, tag, bx0, by0, bz0, bx1, by1, bz1);
    const double e = 1e-3;
    if (bx0 >= x0 - e && bx1 <= x1 + e && std::max({-by0, -bz0, by1, bz1}) <= r + e)
      band.push_back(tag);
  }
  return band;
}

BuiltBody buildCapsule() {
  const double radius = 1.0, noseRadius = 2.4, shoulder = 0.1, cone = 32.5 * kPi / 180;
  const double backRadius = 0.35, backRound = 0.1;
  const double th = std::asin((radius - shoulder) / (noseRadius - shoulder));
  const glm::dvec2 tangent(noseRadius * (1 - std::cos(th)), noseRadius * std::sin(th));
  const glm::dvec2 torus(noseRadius - (noseRadius - shoulder) * std::cos(th),
                         (noseRadius - shoulder) * std::sin(th));
  const glm::dvec2 coneDir(std::cos(cone), -std::sin(cone)),
      coneNormal(std::sin(cone), std::cos(cone));
  const glm::dvec2 coneStart = torus + shoulder * coneNormal;
  const double coneLength = (coneStart.y - backRadius - backRound * coneNormal.y) / std::sin(cone);
  const glm::dvec2 coneEnd = coneStart + coneLength * coneDir;
  const glm::dvec2 roundCentre = coneEnd - backRound * coneNormal;
  const double rearX = roundCentre.x + backRound;

  Profile p(0, 0);
  p.arcTo(tangent.x, tangent.y, noseRadius, 0);
  p.arcTo(coneStart.x, coneStart.y, torus.x, torus.y);
  p.lineTo(coneEnd.x, coneEnd.y);
  p.arcTo(rearX, roundCentre.y, roundCentre.x, roundCentre.y);
  p.lineTo(rearX, 0);
  BuiltBody b;
  b.volume = p.revolve();
  occ::synchronize();
  b.recombine = surfacesInBand(b.volume, coneStart.x, coneEnd.x, radius);  // the afterbody cone
  b.shape.parts.push_back({{0, 0, 0}, {rearX, 0, 0}, radius, kInf});
  b.shape.rearX = rearX;
  return b;
}

glm::dvec3 atAzimuth(double x, double r, double azimuth) {
  return {x, r * std::cos(azimuth), r * std::sin(azimuth)};
}

BuiltBody buildLander() {
  const double radius = 1.0, noseRadius = 2.0, shoulder = 0.12, length = 1.0, backRound = 0.15;
  const double th = std::asin((radius - shoulder) / (noseRadius - shoulder));
  const glm::dvec2 tangent(noseRadius * (1 - std::cos(th)), noseRadius * std::sin(th));
  const glm::dvec2 torus(noseRadius - (noseRadius - shoulder) * std::cos(th), radius - shoulder);
  const double sideStart = torus.x, sideEnd = torus.x + length, backX = sideEnd + backRound;

  Profile p(0, 0);
  p.arcTo(tangent.x, tangent.y, noseRadius, 0);
  p.arcTo(sideStart, radius, torus.x, torus.y);
  p.lineTo(sideEnd, radius);
  p.arcTo(backX, radius - backRound, sideEnd, radius - backRound);
  p.lineTo(backX, 0);
  const int hull = p.revolve();

  BuiltBody b;
  b.shape.parts.push_back({{0, 0, 0}, {backX, 0, 0}, radius, kInf});
  gmsh::vectorpair tools;
  // Azimuths avoid 0, where the revolved surfaces have their seam.
  for (int k = 0; k < 3; ++k) {
    // Nozzles: canted frusta whose bases sit inside the heat shield.
    const double nozzleAz = (30.0 + 120.0 * k) * kPi / 180, cant = 8.0 * kPi / 180;
    const glm::dvec3 base = atAzimuth(0.25, 0.5, nozzleAz);
    const glm::dvec3 exit =
        base + 0.45 * glm::dvec3(-std::cos(cant), std::sin(cant) * std::cos(nozzleAz),
                                 std::sin(cant) * std::sin(nozzleAz));
    const glm::dvec3 axis = exit - base;
    tools.push_back({3, occ::addCone(base.x, base.y, base.z, axis.x, axis.y, axis.z, 0.16, 0.24)});
    b.shape.parts.push_back({base, exit, 0.24, 2 * kPi * 0.16 / 6});
    // Legs on the base, parallel to the axis, with foot pads. Every junction is a right angle:
    // at sharper concave creases (a splayed strut, an elbow) the layer's averaged normals tilt
    // under the wall and gmsh's wedges fold or its layer surfaces cross.
    const double legAz = (90.0 + 120.0 * k) * kPi / 180;
    const glm::dvec3 hip = atAzimuth(backX - 0.1, 0.6, legAz),
                     foot = atAzimuth(backX + 0.9, 0.6, legAz);
    tools.push_back({3, occ::addCylinder(hip.x, hip.y, hip.z, foot.x - hip.x, 0, 0, 0.12)});
    tools.push_back({3, occ::addCylinder(foot.x - 0.1, foot.y, foot.z, 0.2, 0, 0, 0.25)});
    b.shape.parts.push_back({hip, foot, 0.12, 2 * kPi * 0.12 / 6});
    b.shape.parts.push_back(
        {foot - glm::dvec3(0.1, 0, 0), foot + glm::dvec3(0.1, 0, 0), 0.25, 2 * kPi * 0.25 / 7});
  }
  gmsh::vectorpair fused;
  std::vector<gmsh::vectorpair> map;
  occ::fuse({{3, hull}}, tools, fused, map);
  occ::synchronize();
  SM_CHECK_EQ(fused.size(), 1u);
  b.volume = fused[0].second;
  // Quads on the cylindrical side, away from the concave junctions of legs and nozzles, where the
  // pyramids on the layer could poke into the neighbouring layer.
  b.recombine = surfacesInBand(b.volume, sideStart, sideEnd, radius);
  b.shape.rearX = backX + 1.0;
  return b;
}

double distanceToSegment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 ab = b - a;
  const double t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
  return glm::length(p - (a + t * ab));
}

}  // namespace

BuiltBody buildBody(Body body) {
  return body == Body::Lander ? buildLander() : buildCapsule();
}

Box farField(const BodyShape& shape) {
  return {{-6, -7, -7}, {shape.rearX + 14, 7, 7}};
}

Box hexBlockRegion(const BodyShape& shape) {
  return {{shape.rearX + 0.8, -1, -1}, {shape.rearX + 5.8, 1, 1}};
}

SizeLaw::SizeLaw(BodyShape shape, double scale, bool hexBlock)
    : shape_(std::move(shape)),
      scale_(scale),
      hexBlock_(hexBlock),
      block_(hexBlockRegion(shape_)) {}

double SizeLaw::wallSize() const {
  return scale_ * kWallSize;
}
double SizeLaw::hexBlockSize() const {
  return scale_ * kHexSize;
}

double SizeLaw::layerThickness() const {
  double size = wallSize();
  for (const auto& part : shape_.parts) size = std::min(size, part.floor);
  return kLayerFraction * size;
}

double SizeLaw::operator()(const glm::dvec3& p) const {
  double distance = kInf, cap = kInf;
  for (const auto& part : shape_.parts) {
    const double d = distanceToSegment(p, part.a, part.b) - part.radius;
    distance = std::min(distance, std::max(d, 0.0));
    if (d < kFeatureReach) cap = std::min(cap, part.floor);
  }
  double h = kWallSize + kGrowth * distance;
  // The wake: a cone behind the body where sizes grow slowly downstream and fast sideways.
  const double behind = p.x - shape_.rearX;
  if (behind > -0.5) {
    const double along = std::max(behind, 0.0), r = std::hypot(p.y, p.z);
    const double coneRadius = 1.3 + 0.15 * along;
    h = std::min(h, 1.5 * kWallSize + kWakeGrowth * along + 0.5 * std::max(r - coneRadius, 0.0));
  }
  h = scale_ * std::min(h, kMaxSize);
  if (hexBlock_) {
    const glm::dvec3 margin(0.3);
    if (glm::all(glm::greaterThan(p, block_.lo - margin)) &&
        glm::all(glm::lessThan(p, block_.hi + margin)))
      h = std::min(h, hexBlockSize());
  }
  return std::min(h, cap);
}

}  // namespace sm::gen
