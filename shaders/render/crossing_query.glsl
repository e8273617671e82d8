// Shell crossings found with ray queries (compute entry points). crossing_pipeline.glsl finds the
// same ones with a ray tracing pipeline.
#ifndef SM_CROSSING_GLSL
#define SM_CROSSING_GLSL

#extension GL_EXT_ray_query : require

layout(set = 0, binding = 0) uniform accelerationStructureEXT tlas;

// Exact mode: the first crossing with the wanted side after (tPrev, triPrev) in (t, triangle)
// order (crossingComesFirst).
bool exactCrossing(RayFrame fr, SceneRefs sc, float tPrev, uint triPrev, float tMax, int side, out uint tri,
                   out float tBest) {
  rayQueryEXT q;
  rayQueryInitializeEXT(q, tlas, gl_RayFlagsNoneEXT, 0xFF, fr.org, max(tPrev, 0.0), fr.dir, tMax);
  ShellHit h = ShellHit(tPrev, triPrev, tMax, kNoTriangle);
  while (rayQueryProceedEXT(q)) {
    if (rayQueryGetIntersectionTypeEXT(q, false) != gl_RayQueryCandidateIntersectionAABBEXT) continue;
    uint p = uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, false));
    float t;
    if (!shellCandidate(fr, sc, p, side, t) || !crossingComesFirst(t, p, h)) continue;
    h.tri = p;
    h.tBest = t;
    // The device may only prune what lies beyond a committed hit; keep its t inside its range.
    rayQueryGenerateIntersectionEXT(q, clamp(t, max(tPrev, 0.0), tMax));
  }
  tri = h.tri;
  tBest = h.tBest;
  return h.tri != kNoTriangle;
}

// Device mode: the nearest triangle hit beyond tPrev facing the wanted way (-1: entries are the
// front faces, so back faces are culled; +1: exits, front faces culled).
bool deviceCrossing(RayFrame fr, float tPrev, float tMax, int side, out uint tri, out float t) {
  uint flags = gl_RayFlagsOpaqueEXT |
               (side < 0 ? gl_RayFlagsCullBackFacingTrianglesEXT : gl_RayFlagsCullFrontFacingTrianglesEXT);
  rayQueryEXT q;
  rayQueryInitializeEXT(q, tlas, flags, 0xFF, fr.org, deviceSearchStart(tPrev), fr.dir, tMax);
  while (rayQueryProceedEXT(q)) {
  }
  if (rayQueryGetIntersectionTypeEXT(q, true) != gl_RayQueryCommittedIntersectionTriangleEXT) return false;
  tri = uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, true));
  t = rayQueryGetIntersectionTEXT(q, true);
  return true;
}

#endif
