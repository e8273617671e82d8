#version 460
// Two-pass (exact) lists with one traversal. Count pass: trace and march each pixel's ray, keep the
// first segCacheK segments with their fragments in the pixel's cache slots, write the segment
// count (the list's capacity). Store pass, after the prefix sum: copy the cached segments and
// fragments to the pixel's place in the lists; a pixel with more segments than slots traces its
// ray again (the same code on the same data gives the same segments and fragments).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
#include "ray_loop.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 20) const bool kStore = false;
layout(push_constant, scalar) uniform Push { uint64_t params; } pc;

void copyCached(FrameParams fp, uint pixel, uint base, uint n, inout DcListWriter wr) {
  for (uint i = 0u; i < n; ++i) {
    CachedSegment c = SmCachedSegments(fp.segCache).v[pixel * fp.segCacheK + i];
    SmSegments(fp.segments).v[base + i] = c.segment;
    if (c.hasFragment != 0u) dcWrite(wr, DcFragment(c.color, c.depth));
  }
}

void main() {
  FrameParams fp = SmParams(pc.params).p;
  uvec2 px = tiledPixel();
  bool inImage = px.x < fp.width && px.y < fp.height;
  uint pixel = px.y * fp.width + px.x;
  SegmentStats st = noStats();
  uint nseg = 0u, fragments = 0u;
  DcListWriter wr = dcBegin(fp.fragments, 0u, 0u);
  if (kStore) {
    if (!inImage) return;
    uint base = SmUints(fp.segOffsets).v[pixel];
    nseg = SmUints(fp.segCounts).v[pixel];
    wr = dcBegin(fp.fragments, base, nseg);
    if (nseg <= fp.segCacheK)
      copyCached(fp, pixel, base, nseg, wr);
    else  // counted in the count pass already: these statistics are dropped
      traceRay(pixelRay(fp, px), fp, pixel, nseg, RAY_TO_LIST, true, base, wr, fragments, st);
    dcEnd(wr, fp.fragCounts, pixel);
    return;
  }
  if (inImage) {
    nseg = traceRay(pixelRay(fp, px), fp, pixel, fp.maxSegments, RAY_TO_CACHE, false, 0u, wr, fragments, st);
    SmUints(fp.segCounts).v[pixel] = nseg;
  }
  flushStats(fp, st, nseg, fragments, 0u);
}
