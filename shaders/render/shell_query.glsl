// Shell traversal: the segments of this rank's volume along a ray. Entries are found in order with
// the shell's acceleration structure; each segment is then marched from its entry to wherever the
// element walk leaves the volume (so exits come from the exact walk). A ray that starts inside the
// volume has one more segment, found from its first exit.
//
// Versus the paper (exit first, entry found looking back from it): entry-first needs one shell
// query per segment instead of two, and stays right when shells of one rank overlap (pieces that
// were not welded): every entry starts a segment, and the march pass samples each segment only
// beyond where the previous one ended, so an overlap is neither lost nor counted twice.
//
// Who decides that a ray crosses a shell triangle:
//   kExactShell (default): the BLAS holds one padded box per triangle; the device only narrows the
//     search and each candidate is decided by the exact predicates the marcher uses, so traversal
//     and marching can never disagree, also for rays through shell vertices and edges.
//   otherwise: the device's triangle test decides (fast on RT cores); where it disagrees with the
//     exact predicates the marcher walks the shell adjacency (shell_entry.glsl).
#ifndef SM_SHELL_QUERY_GLSL
#define SM_SHELL_QUERY_GLSL

// Two distances along a ray to the same place, computed on different triangles or by different
// formulas (the exact walk and the float box test), differ by rounding; within this (relative)
// they count as the same place. Far thinner than any sample spacing.
const float kSamePlace = 4.0e-6;

// The first crossing after tPrev. With a probe (tPrev < probe < 3e38), the search first stops at
// `probe`: the device then visits only the nodes near where the crossing is expected, instead of
// whatever its traversal order reaches before the first hit prunes the rest. A crossing found
// within the probe is the one the whole ray would give (every triangle crossed before the probe
// is a candidate of both searches, and the first is chosen by the same rule); otherwise the
// search runs again over the whole ray. One query call site either way (a loop, not two calls:
// Mesa inlines each call, and each copy of the query costs compile time).
bool nextCrossing(RayFrame fr, SceneRefs sc, float tPrev, uint triPrev, int side, float probe, out uint tri,
                  out float t, inout uint queries) {
  const float tMax = 3.0e38;
  bool probing = probe > max(tPrev, 0.0) && probe < tMax;
  for (uint attempt = probing ? 0u : 1u; attempt < 2u; ++attempt) {
    float limit = attempt == 0u ? probe : tMax;
    queries += 1u;
    bool found = kExactShell ? exactCrossing(fr, sc, tPrev, triPrev, limit, side, tri, t)
                             : deviceCrossing(fr, tPrev, limit, side, tri, t);
    if (found) return true;
  }
  return false;
}

// Traversal as a state machine with one query call site (Mesa inlines each call; fewer copies of
// the query compile faster). Phase 0 finds the first exit and phase 1 the first entry, only when
// the eye may be inside this rank's volume: an exit before any entry means it is, and that ray's
// first segment starts at the eye. Phase 2 then yields the entries in order.
struct Traversal {
  uint phase;
  float tFirstExit;
  uint firstExit;
  Segment prev;  // last entry yielded (or the search start)
  uint queries;  // acceleration-structure queries made so far (--stats)
};

Segment firstSearchPoint() {
  Segment s;
  s.tEntry = 0.0;
  s.reserved = 0.0;
  s.entryTriangle = kNoTriangle;
  s.exitTriangle = kNoTriangle;
  return s;
}

Traversal beginTraversal(FrameParams fp) {
  Traversal tr;
  tr.phase = fp.eyeMayBeInside != 0u ? 0u : 2u;
  tr.tFirstExit = 0.0;
  tr.firstExit = kNoTriangle;
  tr.prev = firstSearchPoint();
  tr.queries = 0u;
  return tr;
}

// The next segment along the ray; false when there is none. `probe`: where the next crossing is
// expected (nextCrossing), or 0 for none.
bool nextSegment(RayFrame fr, SceneRefs sc, inout Traversal tr, float probe, out Segment seg) {
  seg = firstSearchPoint();
  for (uint guard = 0u; guard < 4u; ++guard) {
    bool entries = tr.phase != 0u;
    uint tri;
    float t;
    bool found = nextCrossing(fr, sc, tr.prev.tEntry, tr.prev.entryTriangle, entries ? -1 : 1, probe, tri, t, tr.queries);
    if (tr.phase == 0u) {
      if (!found) return false;  // no exit ahead at all: nothing of this rank on the ray
      tr.tFirstExit = t;
      tr.firstExit = tri;
      tr.phase = 1u;
      continue;
    }
    if (tr.phase == 1u) {
      tr.phase = 2u;
      // The eye is inside unless an entry comes before the first exit. An entry at the first
      // exit's distance is a neighbouring volume whose face touches this one's (unwelded pieces):
      // computed on other triangles of the same plane, its distance differs from the exit's by
      // rounding, either way, so "before" means by more than that. (An eye outside a volume
      // thinner than that is taken as inside: the walk back from the exit then stops at the
      // volume's entry face, and the segment starts there, as it should.)
      if (!found || t > tr.tFirstExit - kSamePlace * abs(tr.tFirstExit)) {  // a segment starts at the eye
        seg.exitTriangle = tr.firstExit;
        return true;
      }
      continue;  // the eye is outside: phase 2 finds that entry again
    }
    if (!found) return false;
    seg.entryTriangle = tri;
    seg.tEntry = t;
    tr.prev = seg;
    return true;
  }
  return false;
}

#endif
