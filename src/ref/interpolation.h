// Scalar interpolation inside one linear VTK element, in double precision (the reference's half of
// "Scalar at a sample" in docs/ARCHITECTURE.md).
//
// Parametric coordinates and shape functions are VTK's (vtkTetra, vtkPyramid, vtkWedge,
// vtkHexahedron, checked against VTK 9.1):
//   tet      N0 = 1-r-s-t, N1 = r, N2 = s, N3 = t                         (barycentric)
//   pyramid  N0 = (1-r)(1-s)(1-t), N1 = r(1-s)(1-t), N2 = rs(1-t), N3 = (1-r)s(1-t), N4 = t
//   wedge    N0 = (1-r-s)(1-t), N1 = r(1-t), N2 = s(1-t), N3 = (1-r-s)t, N4 = rt, N5 = st
//   hex      N0 = (1-r)(1-s)(1-t), N1 = r(1-s)(1-t), N2 = rs(1-t), N3 = (1-r)s(1-t), N4..N7 the
//            same with t in place of (1-t)
// A world point is mapped to (r, s, t) by solving x(r, s, t) = p: directly for tetrahedra (the map
// is affine), by damped Newton iteration for the others (see worldToParametric). The parametric
// point is then clamped to the element's parametric domain, because points inside the element's
// triangulated boundary can lie slightly outside the curved (bilinear-faced) isoparametric element
// when a quad face is warped; clamping gives them the value on the nearest part of the domain
// instead of an extrapolation.
#pragma once

#include <span>

#include <glm/vec3.hpp>

#include "mesh/cell_type.h"

namespace sm::ref {

inline constexpr int kMaxElementVerts = 8;

// Shape function values N_i(r, s, t), i < numVerts(type).
void shapeFunctions(mesh::CellType type, const glm::dvec3& rst, double* n);
// Their partial derivatives with respect to r, s and t.
void shapeDerivatives(mesh::CellType type, const glm::dvec3& rst, double* dr, double* ds,
                      double* dt);

// x(r, s, t) = sum_i N_i(r, s, t) corners[i].
glm::dvec3 parametricToWorld(mesh::CellType type, std::span<const glm::dvec3> corners,
                             const glm::dvec3& rst);
// The element's parametric centre (the Newton start), the parametric position of vertex v (the
// pyramid's apex, where r and s are arbitrary, at r = s = 0.5), and the nearest point of the
// parametric domain (Euclidean projection in parametric space).
glm::dvec3 parametricCenter(mesh::CellType type);
glm::dvec3 parametricVertex(mesh::CellType type, uint32_t v);
glm::dvec3 clampToDomain(mesh::CellType type, const glm::dvec3& rst);

struct Inversion {
  glm::dvec3 rst{0.0};    // unclamped solution (or the best iterate when not converged)
  double residual = 0.0;  // |x(rst) - p| in world units
  int iterations = 0;     // Newton steps over all starts
  bool converged = false;
};

// Solves x(r, s, t) = p. Tetrahedra: one exact linear solve. Others: Newton's method from the
// parametric centre, each step damped (halved up to 10 times) until the residual decreases, with
// iterates kept in [-1, 2]^3 so a wild step cannot leave for a region where the map folds.
// Converged when a step changes no coordinate by more than 1e-10, or the residual is below
// 1e-14 of the element's size. Up to 40 steps per start; when the centre start fails, starts near
// each vertex are tried; the iterate with the smallest residual is returned either way. Singular
// Jacobians (the pyramid apex, degenerate elements) end a start without NaN.
Inversion worldToParametric(mesh::CellType type, std::span<const glm::dvec3> corners,
                            const glm::dvec3& p);

// The scalar at world point p: shape functions at the clamped parametric point, applied to the
// vertex values. A non-finite vertex value makes the result non-finite (a transparent sample).
double interpolate(mesh::CellType type, std::span<const glm::dvec3> corners,
                   std::span<const double> values, const glm::dvec3& p);

}  // namespace sm::ref
