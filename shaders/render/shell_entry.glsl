// Entering the volume from a shell triangle: reconcile the hardware's triangle with the exact
// predicates, then decode the element behind it.
#ifndef SM_SHELL_ENTRY_GLSL
#define SM_SHELL_ENTRY_GLSL

// From shell triangle `tri` (the hardware's answer), the triangle that the exact predicates say the
// ray crosses with the wanted side (-1 entry, +1 exit); kNoTriangle when the ray only grazes the
// shell there. `walked` counts corrections.
uint confirmShellTriangle(RayFrame fr, SceneRefs sc, uint tri, int side, inout uint walked) {
  SmUints adj = SmUints(sc.shellAdjacency);
  for (uint step = 0u; step < 24u; ++step) {
    uvec3 ids = shellTriangle(sc, tri);
    vec2 p0 = projectVertex(fr, vertexPosition(sc, ids.x)).xy;
    vec2 p1 = projectVertex(fr, vertexPosition(sc, ids.y)).xy;
    vec2 p2 = projectVertex(fr, vertexPosition(sc, ids.z)).xy;
    int s[3] = int[3](edgeSign(p0, p1), edgeSign(p1, p2), edgeSign(p2, p0));
    if (s[0] == side && s[1] == side && s[2] == side) return tri;
    // Step across an edge that has the origin on its wrong side.
    uint next = kNoTriangle;
    for (uint k = 0u; k < 3u && next == kNoTriangle; ++k)
      if (s[k] == -side) next = adj.v[3u * tri + k];
    if (next == kNoTriangle) return kNoTriangle;
    if (step == 0u) walked += 1u;
    tri = next;
  }
  return kNoTriangle;
}

// Sets up a walk that enters the element behind shell triangle `tri` through it (forward, an
// entry) or, for a backward walk from the first exit, through it going backward.
void walkFromShell(RayFrame fr, SceneRefs sc, uint tri, out Walk w) {
  uvec3 ids = shellTriangle(sc, tri);
  w.k = uint[4](ids.x, ids.y, ids.z, 0u);
  w.kn = 3u;
  if (kCompact) {
    uint other = SmUints(sc.shellOther).v[tri];
    if (other != kNoTriangle) {
      w.k[3] = other;
      w.kn = 4u;
    }
  }
  w.next = SmUints(sc.shellRefs).v[tri];
  vec3 p0 = projectVertex(fr, vertexPosition(sc, ids.x));
  vec3 p1 = projectVertex(fr, vertexPosition(sc, ids.y));
  vec3 p2 = projectVertex(fr, vertexPosition(sc, ids.z));
  vec3 bary;
  triangleCrossing(ids.x, ids.y, ids.z, p0, p1, p2, w.tIn, bary, w.slopeIn);
  w.sIn = bary.x * vertexScalar(sc, ids.x) + bary.y * vertexScalar(sc, ids.y) + bary.z * vertexScalar(sc, ids.z);
}

#endif
