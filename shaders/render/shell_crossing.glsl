// The exact decision on one candidate shell triangle, shared by both tracers (the ray query loop
// and the pipeline's intersection shader): the device only narrows the search to the triangles
// whose boxes the ray meets, and these predicates, the marcher's own, decide (shell_query.glsl).
#ifndef SM_SHELL_CROSSING_GLSL
#define SM_SHELL_CROSSING_GLSL

// True when the shell BLAS holds boxes and the exact predicates decide every shell crossing
// (shell_query.glsl); false when the device's triangle test does.
layout(constant_id = 11) const bool kExactShell = true;

uvec3 shellTriangle(SceneRefs sc, uint tri) {
  SmUints idx = SmUints(sc.shellIndices);
  return uvec3(idx.v[3u * tri], idx.v[3u * tri + 1u], idx.v[3u * tri + 2u]);
}

// Whether the ray crosses shell triangle p on `side` (-1 entry, +1 exit), and at which t.
bool shellCandidate(RayFrame fr, SceneRefs sc, uint p, int side, out float t) {
  t = 0.0;
  uvec3 ids = shellTriangle(sc, p);
  vec3 p0 = projectVertex(fr, vertexPosition(sc, ids.x));
  vec3 p1 = projectVertex(fr, vertexPosition(sc, ids.y));
  vec3 p2 = projectVertex(fr, vertexPosition(sc, ids.z));
  if (crossingSide(p0.xy, p1.xy, p2.xy) != side) return false;
  vec3 w;
  vec2 slope;
  triangleCrossing(ids.x, ids.y, ids.z, p0, p1, p2, t, w, slope);
  return true;
}

// Where a device-mode search after a hit at tPrev starts: a few ulps past it, or the device finds
// that hit again.
float deviceSearchStart(float tPrev) {
  float tMin = max(tPrev, 0.0);
  return tMin + max(abs(tMin), 1e-20) * 2e-6;
}

#endif
