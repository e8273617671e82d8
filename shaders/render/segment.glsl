// One segment from traversal to fragment: confirm the entry with the exact predicates, find the
// first element (walking back from the exit when the segment starts inside the volume), march.
#ifndef SM_SEGMENT_GLSL
#define SM_SEGMENT_GLSL

struct SegmentStats {
  uint lost, grazing, walks, stepLimit, steps, samples, inside, boxExits, queries;
};

SegmentStats noStats() { return SegmentStats(0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u); }

// Integrates `seg`, sampling from max(its entry, prevEnd) on; returns false when the segment gives
// no fragment (in device-triangle mode, the exact predicates may say the ray only grazes there).
bool integrateSegment(RayFrame fr, FrameParams fp, Segment seg, inout float prevEnd, out DcFragment frag,
                      inout SegmentStats st) {
  frag.color = vec4(0.0);
  frag.depth = 0.0;
  SceneRefs sc = fp.scene;
  bool inside = seg.entryTriangle == kNoTriangle;
  // Inside: the eye is in the volume; walk back from the first exit to the element holding it.
  uint tri = inside ? seg.exitTriangle : seg.entryTriangle;
  if (!kExactShell) tri = confirmShellTriangle(fr, sc, tri, inside ? 1 : -1, st.walks);
  if (tri == kNoTriangle) {
    st.grazing += 1u;
    return false;
  }
  Walk w;
  walkFromShell(fr, sc, tri, w);
  // One call site for both walks (see march.glsl): phase 0 locates the eye's element, phase 1
  // integrates.
  float tLo = 0.0;
  MarchResult r;
  for (uint phase = inside ? 0u : 1u; phase < 2u; ++phase) {
    if (phase == 1u) tLo = max(w.tIn, max(prevEnd, 0.0));
    r = walk(fr, fp, w, phase == 0u ? -1 : 1, tLo);
    st.steps += r.steps;
    if (r.status != MARCH_OK) break;
  }
  if (inside) st.inside += 1u;
  st.samples += r.samples;
  if (r.status == MARCH_LOST) st.lost += 1u;
  if (r.status == MARCH_STEP_LIMIT) st.stepLimit += 1u;
  if (r.status != MARCH_OK && r.samples == 0u) return false;
  prevEnd = max(prevEnd, r.tEnd);
  frag.color = r.color;
  frag.depth = tLo;
  return true;
}

// Adds this invocation's statistics to the frame's counters (subgroup_ops.glsl: one atomic a
// subgroup where the stage has subgroups).
void flushStats(FrameParams fp, SegmentStats st, uint segments, uint fragments, uint overflow) {
  SmStats s = SmStats(fp.stats);
  SM_FLUSH(s.s.lostRays, st.lost);
  SM_FLUSH(s.s.grazingSkips, st.grazing);
  SM_FLUSH(s.s.entryWalks, st.walks);
  SM_FLUSH(s.s.stepLimitHits, st.stepLimit);
  SM_FLUSH(s.s.cameraInside, st.inside);
  SM_FLUSH(s.s.boxExits, st.boxExits);
  SM_FLUSH(s.s.overflow, overflow);
  SM_FLUSH(s.s.shellQueries, st.queries);
  SM_FLUSH(s.s.segments, segments);
  SM_FLUSH(s.s.fragments, fragments);
  SM_FLUSH_WIDE(s.s.elementSteps, s.s.elementStepsHigh, st.steps);
  SM_FLUSH_WIDE(s.s.samples, s.s.samplesHigh, st.samples);
}

layout(buffer_reference, scalar) readonly buffer SmRays { RayDesc v[]; };

// The pixel of this invocation: tiles of 8 x 8 (stage_*.glsl), invocations in Morton order within
// a tile, so that each run of 8 (one SIMD batch on lavapipe's 256-bit vectors, a quarter of a warp
// elsewhere) is a 4 x 2 block whose rays stay closer together than a row's.
uvec2 smPixel() {
  uvec2 tile;
  uint i;
  smTileAndLane(tile, i);
  uint x = (i & 1u) | ((i >> 1u) & 2u) | ((i >> 2u) & 4u);
  uint y = ((i >> 1u) & 1u) | ((i >> 2u) & 2u) | ((i >> 3u) & 4u);
  return tile * 8u + uvec2(x, y);
}

// The part of the ray that the frame's clip planes keep (scene::clipSpan, in float): [clipLo,
// clipHi) and the grid samples in it. An empty span has clipHi <= clipLo and no samples.
RayFrame clipRay(RayFrame fr, FrameParams fp) {
  float lo = 0.0, hi = 3.0e38;
  for (uint i = 0u; i < fp.clipCount; ++i) {
    vec4 p = fp.clipPlanes[i];
    float side = dot(p.xyz, fr.org) + p.w, rate = dot(p.xyz, fr.dir);
    if (rate == 0.0) {
      if (!(side >= 0.0)) hi = -1.0;
      continue;
    }
    float t = -side / rate;
    if (rate > 0.0) lo = max(lo, t);
    else hi = min(hi, t);
  }
  fr.clipLo = lo;
  fr.clipHi = hi;
  fr.kClipLo = firstSample(lo, fp.dt);
  fr.kClipHi = hi > lo ? firstSample(hi, fp.dt) : fr.kClipLo;
  return fr;
}

RayFrame pixelRay(FrameParams fp, uvec2 px) {
  RayFrame fr;
  if (fp.rays != 0ul) {
    RayDesc r = SmRays(fp.rays).v[px.y * fp.width + px.x];
    fr = makeRayFrame(r.origin, r.direction);
  } else {
    fr = cameraRay(fp, px);
  }
  return kClip ? clipRay(fr, fp) : fr;
}

#endif
