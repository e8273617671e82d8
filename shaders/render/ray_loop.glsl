// One ray's segments, traversed and marched together: each segment is integrated as soon as
// traversal finds it, so the ray stops at the first of: no entry left, early termination, or a
// segment that leaves through this rank's bounding box (nothing of the rank lies beyond it, so
// the query that would only confirm "no entry left" is skipped; for a CFD far field, usually a
// box, that is most rays and about half the shell queries).
#ifndef SM_RAY_LOOP_GLSL
#define SM_RAY_LOOP_GLSL

// Where the ray enters (x, 0 when it starts inside) and leaves (y) this rank's bounding box;
// (0, 3e38) without bounds. Slabs parallel to the ray bound nothing.
vec2 boxSpan(RayFrame fr, FrameParams fp) {
  vec2 span = vec2(0.0, 3.0e38);
  if (fp.boundsValid == 0u) return span;
  for (int i = 0; i < 3; ++i) {
    if (fr.dir[i] == 0.0) continue;
    float lo = (fp.boundsLo[i] - fr.org[i]) / fr.dir[i], hi = (fp.boundsHi[i] - fr.org[i]) / fr.dir[i];
    span.x = max(span.x, min(lo, hi));
    span.y = min(span.y, max(lo, hi));
  }
  return span;
}

// True once a walk that ended at tEnd has left the box: the exact walk and the float box test
// round differently, so within a few ulps of the box counts as on it (what could lie between is
// a sliver far thinner than any sample spacing).
bool pastBox(float tEnd, float tBox) {
  return tEnd >= tBox - kSamePlace * abs(tBox);
}

// Where the segments go: into the pixel's fragment list (fixed-length lists; overflow pixels of
// cached two-pass lists, which also store their segments), or into the pixel's cache slots.
const uint RAY_TO_LIST = 0u;
const uint RAY_TO_CACHE = 1u;

// Traces pixel `pixel`'s ray up to `cap` segments; returns how many it found. `fragments` counts
// the fragments a list would keep (non-zero opacity).
uint traceRay(RayFrame fr, FrameParams fp, uint pixel, uint cap, uint sink, bool storeSegments,
              uint segBase, inout DcListWriter wr, inout uint fragments, inout SegmentStats st) {
  vec2 box = boxSpan(fr, fp);
  float tBoxIn = box.x, tBox = box.y;
  // A ray that misses the box misses the volume: no query for it.
  if (tBox < tBoxIn - kSamePlace * abs(tBoxIn)) return 0u;
  // Nor does one whose clip span is empty or outside the box.
  if (kClip && (!(fr.clipHi > fr.clipLo) || fr.clipHi < tBoxIn - kSamePlace * abs(tBoxIn) ||
                fr.clipLo > tBox + kSamePlace * abs(tBox)))
    return 0u;
  // The next entry is most often where the ray enters the box (a far field fills its box) or
  // where the last segment ended (clusters side by side): probe there first (nextCrossing), a
  // thousandth of the box's depth on, far more than float rounding of either.
  float probeDepth = tBox < 3.0e38 && tBox > tBoxIn ? 1e-3 * (tBox - tBoxIn) : 0.0;
  float prevEnd = 0.0, transmittance = 1.0;
  Traversal tr = beginTraversal(fp);
  Segment seg;
  uint n = 0u;
  while (n < cap) {
    float probe = probeDepth > 0.0 ? max(tBoxIn, prevEnd) + probeDepth : 0.0;
    if (!nextSegment(fr, fp.scene, tr, probe, seg)) break;
    DcFragment frag;
    bool has = integrateSegment(fr, fp, seg, prevEnd, frag, st);
    if (storeSegments) SmSegments(fp.segments).v[segBase + n] = seg;
    if (sink == RAY_TO_CACHE) {
      if (n < fp.segCacheK)
        SmCachedSegments(fp.segCache).v[pixel * fp.segCacheK + n] =
            CachedSegment(seg, frag.color, frag.depth, has ? 1u : 0u);
    } else if (has) {
      dcWrite(wr, frag);
    }
    n += 1u;
    if (has && frag.color.a > 0.0) fragments += 1u;
    if (has) {
      transmittance *= 1.0 - frag.color.a;
      if (1.0 - transmittance >= fp.earlyTermination) break;
    }
    if (kClip && prevEnd >= fr.clipHi) break;  // the rest of the ray is clipped away
    if (pastBox(prevEnd, tBox)) {
      st.boxExits += 1u;
      break;
    }
  }
  st.queries += tr.queries;
  return n;
}

#endif
