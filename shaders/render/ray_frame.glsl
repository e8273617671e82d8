// Watertight crossing predicates (docs/DESIGN.md invariant 2).
//
// Every vertex is mapped into a ray-centric frame (Woop, Benthin, Wald 2013: permute the axes so
// that the ray runs along +z, shear x and y by the direction). A face contains the ray when the
// origin of the projected plane lies inside its projected triangle, decided by the signs of the
// three edge functions p x q. Those signs are computed *exactly* from the projected float
// coordinates (a float result is either correctly signed or zero; zero falls back to double, where
// products of floats are exact), and an exact zero is broken by a symbolic perturbation of the
// origin by (eps, eps^2). The sign of an edge is therefore a function of the edge alone, the same in
// every element and every rank that evaluates it, and antisymmetric in its two endpoints. Together
// these make the crossings of one ray with a closed triangulated surface consistent: a ray can
// never slip between two elements sharing a face, nor be claimed by both.
#ifndef SM_RAY_FRAME_GLSL
#define SM_RAY_FRAME_GLSL

layout(constant_id = 10) const bool kHasFloat64 = false;

// Pipelines for frames with clip planes (FrameParams::clipPlanes); without, the clip code is
// compiled out and costs nothing.
layout(constant_id = 14) const bool kClip = false;

struct RayFrame {
  vec3 org;
  vec3 dir;
  uint kx, ky, kz;
  float sx, sy, sz;
  // kClip: the ray's samples are those of [clipLo, clipHi), grid indices [kClipLo, kClipHi)
  // (segment.glsl, clipRay).
  float clipLo, clipHi;
  uint kClipLo, kClipHi;
};

RayFrame makeRayFrame(vec3 org, vec3 dir) {
  RayFrame f;
  f.org = org;
  f.dir = dir;
  vec3 a = abs(dir);
  f.kz = a.x > a.y ? (a.x > a.z ? 0u : 2u) : (a.y > a.z ? 1u : 2u);
  f.kx = (f.kz + 1u) % 3u;
  f.ky = (f.kx + 1u) % 3u;
  if (dir[f.kz] < 0.0) {  // keep the frame right-handed so that windings keep their meaning
    uint t = f.kx;
    f.kx = f.ky;
    f.ky = t;
  }
  f.sx = dir[f.kx] / dir[f.kz];
  f.sy = dir[f.ky] / dir[f.kz];
  f.sz = 1.0 / dir[f.kz];
  f.clipLo = 0.0;
  f.clipHi = 3.0e38;
  f.kClipLo = 0u;
  f.kClipHi = 0xFFFFFFFFu;
  return f;
}

// The camera ray through the centre of pixel px (scene::CameraFrame, the one definition): from the
// eye, or with a parallel projection from the image plane through the eye, along forward. Every
// rank computes the same float origin and direction for a pixel, so t (and the sample grid
// t_k = k dt, and fragment depths) mean the same on every rank.
RayFrame cameraRay(FrameParams fp, uvec2 px) {
  float u = (2.0 * (float(px.x) + 0.5) / float(fp.width) - 1.0) * fp.halfHeight * fp.aspect;
  float v = (1.0 - 2.0 * (float(px.y) + 0.5) / float(fp.height)) * fp.halfHeight;
  if (fp.parallel != 0u)
    return makeRayFrame(fp.eye + u * fp.right + v * fp.upOrtho, normalize(fp.forward));
  return makeRayFrame(fp.eye, normalize(fp.forward + u * fp.right + v * fp.upOrtho));
}

// xy: the vertex projected along the ray; z: the ray distance of the vertex's foot point.
vec3 projectVertex(RayFrame f, vec3 p) {
  precise vec3 a = p - f.org;
  precise float x = a[f.kx] - f.sx * a[f.kz];
  precise float y = a[f.ky] - f.sy * a[f.kz];
  precise float z = f.sz * a[f.kz];
  return vec3(x, y, z);
}

// Exact sign of p x q (orientation of the origin against directed edge p -> q), never zero unless
// the edge itself is degenerate in projection; sign(q, p) == -sign(p, q).
int edgeSign(vec2 p, vec2 q) {
  precise float e = p.x * q.y - p.y * q.x;
  if (e > 0.0) return 1;
  if (e < 0.0) return -1;
  if (kHasFloat64) {
    double d = double(p.x) * double(q.y) - double(p.y) * double(q.x);
    if (d > 0.0lf) return 1;
    if (d < 0.0lf) return -1;
  } else {
    // Error-free products: x*y = hi + lo exactly when fma is fused (true of GPUs and llvmpipe).
    precise float h1 = p.x * q.y;
    precise float l1 = fma(p.x, q.y, -h1);
    precise float h2 = p.y * q.x;
    precise float l2 = fma(p.y, q.x, -h2);
    if (h1 == h2) {
      precise float l = l1 - l2;
      if (l > 0.0) return 1;
      if (l < 0.0) return -1;
    }
  }
  // The origin lies exactly on the edge's line: perturb it by (eps, eps^2). Then
  // sign = sign((q - p) x (eps, eps^2)) = -sign(q.y - p.y), or sign(q.x - p.x) if that is zero.
  precise float dy = q.y - p.y;
  if (dy != 0.0) return dy < 0.0 ? 1 : -1;
  precise float dx = q.x - p.x;
  if (dx != 0.0) return dx > 0.0 ? 1 : -1;
  return 0;
}

// +1 when the ray leaves through outward-wound triangle (a, b, c) (counter-clockwise in the frame),
// -1 when it enters through it (clockwise), 0 when the origin is outside it.
int crossingSide(vec2 a, vec2 b, vec2 c) {
  int s0 = edgeSign(a, b);
  int s1 = edgeSign(b, c);
  int s2 = edgeSign(c, a);
  if (s0 == s1 && s1 == s2) return s0;
  return 0;
}

// Where the ray crosses triangle (ids ia, ib, ic; projected pa, pb, pc): distance t, barycentric
// weights (of a, b, c), and the slopes (a, b) of the triangle's plane in the frame, z = t + a x + b y.
// The slopes order crossings that tie in t as the perturbed ray (moved by (eps, eps^2)) meets them:
// at t + a eps + b eps^2. Computed in ascending id order so that every element (on every rank)
// sharing the face gets bit-identical results.
void triangleCrossing(uint ia, uint ib, uint ic, vec3 pa, vec3 pb, vec3 pc, out float t, out vec3 w,
                      out vec2 slope) {
  vec3 p0 = pa, p1 = pb, p2 = pc;
  uvec3 slot = uvec3(0u, 1u, 2u);  // where each sorted vertex came from
  uint i0 = ia, i1 = ib, i2 = ic;
  if (i1 < i0) { uint ti = i0; i0 = i1; i1 = ti; vec3 tp = p0; p0 = p1; p1 = tp; slot.xy = slot.yx; }
  if (i2 < i1) { uint ti = i1; i1 = i2; i2 = ti; vec3 tp = p1; p1 = p2; p2 = tp; slot.yz = slot.zy; }
  if (i1 < i0) { uint ti = i0; i0 = i1; i1 = ti; vec3 tp = p0; p0 = p1; p1 = tp; slot.xy = slot.yx; }
  precise float u = p1.x * p2.y - p1.y * p2.x;
  precise float v = p2.x * p0.y - p2.y * p0.x;
  precise float s = p0.x * p1.y - p0.y * p1.x;
  precise float det = u + v + s;
  vec3 ws;
  slope = vec2(0.0);
  if (det != 0.0) {
    precise float num = u * p0.z + v * p1.z + s * p2.z;
    t = num / det;
    ws = vec3(u, v, s) / det;
    precise vec3 d1 = p1 - p0;
    precise vec3 d2 = p2 - p0;
    precise float area = d1.x * d2.y - d2.x * d1.y;
    if (area != 0.0) {
      precise float sa = d1.z * d2.y - d2.z * d1.y;
      precise float sb = d1.x * d2.z - d2.x * d1.z;
      slope = vec2(sa / area, sb / area);
    }
  } else {  // edge-on in float: the three feet agree to rounding
    t = (p0.z + p1.z + p2.z) / 3.0;
    ws = vec3(1.0 / 3.0);
  }
  w[slot.x] = ws.x;
  w[slot.y] = ws.y;
  w[slot.z] = ws.z;
}

// Crossing order along the perturbed ray: by t, and where two crossings lie at the same point (a ray
// through a vertex or edge), by the slopes. The same point reached through different triangles gets
// t values that differ by rounding (the formula weighs different vertices), so t within a few ulps
// counts as a tie.
bool crossingBefore(float t0, vec2 s0, float t1, vec2 s1) {
  float tolerance = (abs(t0) + abs(t1)) * 4.8e-7;
  if (abs(t0 - t1) > tolerance) return t0 < t1;
  if (s0.x != s1.x) return s0.x < s1.x;
  return s0.y < s1.y;
}

#endif
