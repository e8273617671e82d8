// Shell-to-shell traversal (the paper's "Per-Node Segment Generation via Shell Traversal"): a ray
// traced from tMin with front faces culled finds the next exit from this rank's volume; a ray
// traced back from that exit, again culling front faces, finds the entry that belongs to it. Gaps
// and overlaps between clusters are then harmless: each segment is an entry/exit pair of one
// closed shell. Hardware (or lavapipe) decides which triangle a ray hits with its own watertight
// test; where that disagrees with our exact predicates (a ray within rounding of a shell edge or
// vertex) we walk the shell's edge adjacency to the triangle our predicates choose.
#ifndef SM_SHELL_QUERY_GLSL
#define SM_SHELL_QUERY_GLSL

#extension GL_EXT_ray_query : require

#include "shell_entry.glsl"

layout(set = 0, binding = 0) uniform accelerationStructureEXT tlas;

const uint kShellRayFlags = gl_RayFlagsOpaqueEXT | gl_RayFlagsCullFrontFacingTrianglesEXT;

// Distance past an exit at which the search for the next one resumes: a few ulps of t, so the same
// triangle is not found again.
float resumeAfter(float t) { return t + max(abs(t), 1e-20) * 2e-6; }

// Next segment beyond tMin: false when the ray has left this rank's volume for good.
bool nextSegment(RayFrame fr, float tMin, float tMax, out Segment seg) {
  rayQueryEXT q;
  rayQueryInitializeEXT(q, tlas, kShellRayFlags, 0xFF, fr.org, tMin, fr.dir, tMax);
  while (rayQueryProceedEXT(q)) {
  }
  if (rayQueryGetIntersectionTypeEXT(q, true) != gl_RayQueryCommittedIntersectionTriangleEXT) return false;
  float tx = rayQueryGetIntersectionTEXT(q, true);
  seg.tStart = tMin;
  seg.tExit = tx;
  seg.exitTriangle = uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, true));
  seg.entryTriangle = kNoTriangle;
  float back = tx - tMin;
  if (back > 0.0) {
    rayQueryEXT b;
    rayQueryInitializeEXT(b, tlas, kShellRayFlags, 0xFF, fr.org + tx * fr.dir, 0.0, -fr.dir, back);
    while (rayQueryProceedEXT(b)) {
    }
    if (rayQueryGetIntersectionTypeEXT(b, true) == gl_RayQueryCommittedIntersectionTriangleEXT)
      seg.entryTriangle = uint(rayQueryGetIntersectionPrimitiveIndexEXT(b, true));
  }
  return true;
}

#endif
