// Exact-as-possible ray / element intersection: the interval(s) of a ray inside one element's
// triangulated boundary (faces from the shared face table, quads split by gpu::smQuadSplit on
// global vertex ids).
//
// Each triangle is tested in Woop, Benthin and Wald's sheared ray frame ("Watertight ray/triangle
// intersection", JCGT 2013), in double precision, with two additions that make the result a
// function of the geometry alone:
//  - Canonical order. A triangle's vertices are sorted by global id before its edge functions and
//    its hit distance are evaluated, so the elements on both sides of a shared face compute the
//    same numbers bit for bit: a conforming mesh yields t_out of one element == t_in of the next.
//  - Symbolic perturbation. An edge function that is exactly zero (the ray passes through an edge
//    or a vertex) takes the sign it would have if the ray were shifted by an infinitesimal
//    (eps, eps^2) in the sheared frame. Every decision is then the decision for one generic
//    ray, so a ray through a vertex or along an edge enters and leaves each element exactly once
//    (or not at all), never twice and never leaking. Triangles seen exactly edge-on are skipped
//    (the shifted ray misses them), so rays in the plane of a face are handled by the other faces.
// Hits are classified as entering (front-facing: the outward normal faces the ray) or leaving,
// sorted, and the element's intervals are where the running count (entries minus exits) is
// positive. For a convex element that is one interval; a warped non-convex one can give two.
// An inverted element (faces wound inward) leaves first and therefore yields nothing; a
// zero-length interval (grazing a vertex or an edge) is dropped.
#pragma once

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "mesh/cell_type.h"

namespace sm::ref {

// A ray in the sheared frame: z along the ray, x and y across it.
class RayFrame {
 public:
  RayFrame(const glm::dvec3& origin, const glm::dvec3& dir);  // dir must be non-zero and finite
  // The point relative to the origin in the sheared frame; z is scaled so that a hit's distance
  // is in units of |dir|.
  glm::dvec3 project(const glm::dvec3& p) const;

 private:
  glm::dvec3 origin_;
  int kx_ = 0, ky_ = 1, kz_ = 2;
  double sx_ = 0, sy_ = 0, sz_ = 1;
};

struct Interval {
  double tIn, tOut;
};

// The most intervals one element can produce (its hits pair up: at most 12 triangles).
inline constexpr int kMaxElementIntervals = 6;

// Intervals (in units of |dir|, over the whole line, possibly negative) where the ray is inside
// the element with global vertex ids `ids`; returns how many were written to `out`.
int elementIntervals(const RayFrame& ray, mesh::CellType type, std::span<const uint32_t> ids,
                     std::span<const glm::dvec3> points, Interval* out);

}  // namespace sm::ref
