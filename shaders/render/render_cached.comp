#version 460
// Two-pass (exact) lists with one traversal. Count pass: trace and march each pixel's ray, keep the
// first segCacheK segments with their fragments in the pixel's cache slots, write the segment
// count (the list's capacity). Store pass, after the prefix sum: copy the cached segments and
// fragments to the pixel's place in the lists; a pixel with more segments than slots traces its
// ray again (the same code on the same data gives the same segments and fragments).
//
// One pipeline for both passes (the pass is a push constant, not a specialisation constant) and one
// call site of traceRay: the tracer is most of the shader, and each copy of it costs lavapipe
// about two seconds to compile when a renderer is first used.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
#include "ray_loop.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push {
  uint64_t params;
  uint store;  // 0: count pass, 1: store pass
} pc;

void copyCached(FrameParams fp, uint pixel, uint base, uint n, inout DcListWriter wr) {
  for (uint i = 0u; i < n; ++i) {
    CachedSegment c = SmCachedSegments(fp.segCache).v[pixel * fp.segCacheK + i];
    SmSegments(fp.segments).v[base + i] = c.segment;
    if (c.hasFragment != 0u) dcWrite(wr, DcFragment(c.color, c.depth));
  }
}

void main() {
  FrameParams fp = SmParams(pc.params).p;
  bool store = pc.store != 0u;
  uvec2 px = tiledPixel();
  bool inImage = px.x < fp.width && px.y < fp.height;
  uint pixel = px.y * fp.width + px.x;
  SegmentStats st = noStats();
  uint nseg = 0u, fragments = 0u, base = 0u;
  DcListWriter wr = dcBegin(fp.fragments, 0u, 0u);
  bool trace = inImage;
  if (store && inImage) {
    base = SmUints(fp.segOffsets).v[pixel];
    nseg = SmUints(fp.segCounts).v[pixel];
    wr = dcBegin(fp.fragments, base, nseg);
    trace = nseg > fp.segCacheK;
    if (!trace) copyCached(fp, pixel, base, nseg, wr);
  }
  if (trace) {
    uint n = traceRay(pixelRay(fp, px), fp, pixel, store ? nseg : fp.maxSegments,
                      store ? RAY_TO_LIST : RAY_TO_CACHE, store, base, wr, fragments, st);
    if (!store) {
      nseg = n;
      SmUints(fp.segCounts).v[pixel] = nseg;
    }
  }
  if (store) {
    if (inImage) dcEnd(wr, fp.fragCounts, pixel);
    return;  // counted in the count pass already: a retraced pixel's statistics are dropped
  }
  flushStats(fp, st, nseg, fragments, 0u);
}
