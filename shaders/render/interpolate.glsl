// Scalar interpolation inside an element: barycentric in tetrahedra (done on the faces by the
// marcher), VTK's isoparametric shape functions in pyramids, wedges and hexahedra, inverted by
// Newton's method to 1e-6 in parametric space.
//
// The arrays here are indexed by constants only (the loops over the eight shape functions are
// unrolled; entries past the element's vertex count are zero): lavapipe keeps such arrays in vector
// registers, while a dynamic index turns every access into per-lane scalar loads and stores. Adding
// the zero terms leaves every sum unchanged.
#ifndef SM_INTERPOLATE_GLSL
#define SM_INTERPOLATE_GLSL

#include "shared/cell_tables.h"

// Shape functions N[i] and their derivatives dN[i] = (dN/dr, dN/ds, dN/dt) at parametric point p.
void shapeFunctions(uint type, vec3 p, out float N[8], out vec3 dN[8]) {
  float r = p.x, s = p.y, t = p.z;
  N = float[8](0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
  dN = vec3[8](vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
  if (type == SM_HEX) {
    float rm = 1.0 - r, sm = 1.0 - s, tm = 1.0 - t;
    N[0] = rm * sm * tm; N[1] = r * sm * tm; N[2] = r * s * tm; N[3] = rm * s * tm;
    N[4] = rm * sm * t;  N[5] = r * sm * t;  N[6] = r * s * t;  N[7] = rm * s * t;
    dN[0] = vec3(-sm * tm, -rm * tm, -rm * sm); dN[1] = vec3(sm * tm, -r * tm, -r * sm);
    dN[2] = vec3(s * tm, r * tm, -r * s);       dN[3] = vec3(-s * tm, rm * tm, -rm * s);
    dN[4] = vec3(-sm * t, -rm * t, rm * sm);    dN[5] = vec3(sm * t, -r * t, r * sm);
    dN[6] = vec3(s * t, r * t, r * s);          dN[7] = vec3(-s * t, rm * t, rm * s);
  } else if (type == SM_WED) {
    float u = 1.0 - r - s, tm = 1.0 - t;
    N[0] = u * tm; N[1] = r * tm; N[2] = s * tm; N[3] = u * t; N[4] = r * t; N[5] = s * t;
    dN[0] = vec3(-tm, -tm, -u); dN[1] = vec3(tm, 0.0, -r); dN[2] = vec3(0.0, tm, -s);
    dN[3] = vec3(-t, -t, u);    dN[4] = vec3(t, 0.0, r);   dN[5] = vec3(0.0, t, s);
  } else {  // pyramid
    float rm = 1.0 - r, sm = 1.0 - s, tm = 1.0 - t;
    N[0] = rm * sm * tm; N[1] = r * sm * tm; N[2] = r * s * tm; N[3] = rm * s * tm; N[4] = t;
    dN[0] = vec3(-sm * tm, -rm * tm, -rm * sm); dN[1] = vec3(sm * tm, -r * tm, -r * sm);
    dN[2] = vec3(s * tm, r * tm, -r * s);       dN[3] = vec3(-s * tm, rm * tm, -rm * s);
    dN[4] = vec3(0.0, 0.0, 1.0);
  }
}

vec3 parametricCenter(uint type) {
  if (type == SM_WED) return vec3(1.0 / 3.0, 1.0 / 3.0, 0.5);
  if (type == SM_PYR) return vec3(0.5, 0.5, 0.2);
  return vec3(0.5);
}

vec3 isoparametricPosition(uint type, vec3 P[8], vec3 p) {
  float N[8];
  vec3 dN[8];
  shapeFunctions(type, p, N, dN);
  vec3 x = vec3(0.0);
  [[unroll]] for (uint i = 0u; i < 8u; ++i) x += N[i] * P[i];
  return x;
}

// Parametric coordinates of x in the element with corner positions P (any common origin for P and
// x; zero past the element's vertices). `p` is the starting guess and receives the result. Newton's
// method with step halving on the residual, so that it converges from the element centre even in
// strongly warped cells; points just outside the element (between a warped face and its two
// triangles) converge to coordinates just outside [0, 1], which interpolateIsoparametric clamps.
void invertIsoparametric(uint type, vec3 P[8], vec3 x, inout vec3 p) {
  vec3 res = isoparametricPosition(type, P, p) - x;
  float rn = dot(res, res);
  SM_NO_UNROLL for (int it = 0; it < 16; ++it) {
    float N[8];
    vec3 dN[8];
    shapeFunctions(type, p, N, dN);
    mat3 J = mat3(0.0);  // columns: d(position)/dr, /ds, /dt
    [[unroll]] for (uint i = 0u; i < 8u; ++i) {
      J[0] += dN[i].x * P[i];
      J[1] += dN[i].y * P[i];
      J[2] += dN[i].z * P[i];
    }
    if (!(abs(determinant(J)) > 1e-30)) return;
    vec3 delta = -(inverse(J) * res);
    bool accepted = false;
    vec3 pn = p, rnext = res;
    float rnn = rn;
    SM_NO_UNROLL for (int h = 0; h < 6 && !accepted; ++h) {
      pn = clamp(p + delta, vec3(-1.0), vec3(2.0));
      rnext = isoparametricPosition(type, P, pn) - x;
      rnn = dot(rnext, rnext);
      accepted = rnn < rn || max(abs(delta.x), max(abs(delta.y), abs(delta.z))) <= 1e-6;
      delta *= 0.5;
    }
    if (!accepted) return;  // no descent along the Newton direction: as good as it gets
    vec3 moved = abs(pn - p);
    p = pn;
    res = rnext;
    rn = rnn;
    if (max(moved.x, max(moved.y, moved.z)) <= 1e-6) return;
  }
}

// Position and Jacobian (columns d/dr, d/ds, d/dt) at parametric point p, from one evaluation of
// the shape functions.
void positionAndJacobian(uint type, vec3 P[8], vec3 p, out vec3 x, out mat3 J) {
  float N[8];
  vec3 dN[8];
  shapeFunctions(type, p, N, dN);
  x = vec3(0.0);
  J = mat3(0.0);
  [[unroll]] for (uint i = 0u; i < 8u; ++i) {
    x += N[i] * P[i];
    J[0] += dN[i].x * P[i];
    J[1] += dN[i].y * P[i];
    J[2] += dN[i].z * P[i];
  }
}

// invertIsoparametric for element-exact integration, whose guesses are close (the entry face, a
// step along the Jacobian): the same tolerance and step halving, but the position comes with the
// Jacobian from one evaluation of the shape functions, and a Newton step within the tolerance is
// taken and ends the search instead of costing another iteration to confirm. Jinv receives the
// inverse Jacobian at the last point evaluated (zero if none was invertible).
void solveIsoparametric(uint type, vec3 P[8], vec3 x, inout vec3 p, out mat3 Jinv) {
  vec3 res;
  mat3 J;
  positionAndJacobian(type, P, p, res, J);
  res -= x;
  float rn = dot(res, res);
  Jinv = mat3(0.0);
  SM_NO_UNROLL for (int it = 0; it < 16; ++it) {
    if (!(abs(determinant(J)) > 1e-30)) return;
    Jinv = inverse(J);
    vec3 delta = -(Jinv * res);
    if (max(abs(delta.x), max(abs(delta.y), abs(delta.z))) <= 1e-6) {
      p = clamp(p + delta, vec3(-1.0), vec3(2.0));
      return;
    }
    bool accepted = false;
    vec3 pn = p, rnext = res;
    mat3 Jn = J;
    float rnn = rn;
    SM_NO_UNROLL for (int h = 0; h < 6 && !accepted; ++h) {
      pn = clamp(p + delta, vec3(-1.0), vec3(2.0));
      positionAndJacobian(type, P, pn, rnext, Jn);
      rnext -= x;
      rnn = dot(rnext, rnext);
      accepted = rnn < rn;
      delta *= 0.5;
    }
    if (!accepted) return;  // no descent along the Newton direction: as good as it gets
    p = pn;
    res = rnext;
    rn = rnn;
    J = Jn;
  }
}

// One Newton step from p toward the parametric point of x: from a guess within e of it, what
// remains is of the order of e squared.
void correctIsoparametric(uint type, vec3 P[8], vec3 x, inout vec3 p) {
  vec3 pos;
  mat3 J;
  positionAndJacobian(type, P, p, pos, J);
  if (abs(determinant(J)) > 1e-30) p = clamp(p - inverse(J) * (pos - x), vec3(-1.0), vec3(2.0));
}

// Euclidean projection of (r, s) onto the triangle r, s >= 0, r + s <= 1.
vec2 projectToTriangle(vec2 q) {
  if (max(q.x, 0.0) + max(q.y, 0.0) <= 1.0) return max(q, vec2(0.0));
  float hi = max(q.x, q.y), lo = min(q.x, q.y);
  float theta = hi - 1.0;
  float c = (hi + lo - 1.0) * 0.5;
  if (lo - c > 0.0) theta = c;
  return max(q - vec2(theta), vec2(0.0));
}

float interpolateIsoparametric(uint type, vec3 p, float S[8]) {
  float N[8];
  vec3 dN[8];
  vec3 q = clamp(p, vec3(0.0), vec3(1.0));
  if (type == SM_WED) q.xy = projectToTriangle(p.xy);
  shapeFunctions(type, q, N, dN);
  float s = 0.0;
  [[unroll]] for (uint i = 0u; i < 8u; ++i) s += N[i] * S[i];
  return s;
}

#endif
