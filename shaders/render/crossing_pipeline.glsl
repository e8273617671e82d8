// Shell crossings found with a ray tracing pipeline (ray generation entry points), for devices
// that offer ray tracing pipelines but not ray queries (NVIDIA's GPUs without RT cores). The same
// crossings as crossing_query.glsl: in exact mode the intersection shader (shell_hit.rint) applies
// shellCandidate to each box the ray meets and the any-hit shader (shell_hit.rahit) keeps the first
// in crossingComesFirst's order in the payload; every reported hit it accepts shrinks the ray so
// that the device prunes what lies beyond, as the query's generated intersections do.
#ifndef SM_CROSSING_GLSL
#define SM_CROSSING_GLSL

layout(set = 0, binding = 0) uniform accelerationStructureEXT tlas;
layout(location = 0) rayPayloadEXT ShellHit shellHit;

// Hit groups in the shader binding table: exact mode has one per side (the side is the
// intersection shader's specialisation), device mode one for triangle hits.
const uint kEntryHitGroup = 0u;
const uint kExitHitGroup = 1u;

bool exactCrossing(RayFrame fr, SceneRefs sc, float tPrev, uint triPrev, float tMax, int side, out uint tri,
                   out float tBest) {
  shellHit = ShellHit(tPrev, triPrev, tMax, kNoTriangle);
  traceRayEXT(tlas, gl_RayFlagsNoOpaqueEXT | gl_RayFlagsSkipClosestHitShaderEXT, 0xFF,
              side < 0 ? kEntryHitGroup : kExitHitGroup, 0, 0, fr.org, max(tPrev, 0.0), fr.dir, tMax, 0);
  tri = shellHit.tri;
  tBest = shellHit.tBest;
  return shellHit.tri != kNoTriangle;
}

bool deviceCrossing(RayFrame fr, float tPrev, float tMax, int side, out uint tri, out float t) {
  uint flags = gl_RayFlagsOpaqueEXT |
               (side < 0 ? gl_RayFlagsCullBackFacingTrianglesEXT : gl_RayFlagsCullFrontFacingTrianglesEXT);
  shellHit = ShellHit(tPrev, kNoTriangle, tMax, kNoTriangle);
  traceRayEXT(tlas, flags, 0xFF, 0, 0, 0, fr.org, deviceSearchStart(tPrev), fr.dir, tMax, 0);
  tri = shellHit.tri;
  t = shellHit.tBest;
  return shellHit.tri != kNoTriangle;
}

#endif
