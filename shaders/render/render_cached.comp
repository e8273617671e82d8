#version 460
// Two-pass (exact) lists with one traversal. Count pass: trace and march each pixel's ray, keep the
// first segCacheK segments with their fragments in the pixel's cache slots, write the segment
// count (the list's capacity) and count the pixels with more segments than slots. Store pass,
// after the prefix sum: store_cached.comp copies the cached fragments (and segments, if kept) to
// the pixel's place in the lists; this pipeline's store pass, dispatched only when some pixel has
// more segments than slots, traces those pixels' rays again (the same code on the same data gives
// the same segments and fragments).
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
    nseg = SmUints(fp.segCounts).v[pixel];
    trace = nseg > fp.segCacheK;  // else store_cached.comp copied the pixel's cache
  }
  if (store && !trace) return;
  if (store) {
    base = SmUints(fp.segOffsets).v[pixel];
    wr = dcBegin(fp.fragments, base, nseg);
  }
  if (trace) {
    uint n = traceRay(pixelRay(fp, px), fp, pixel, store ? nseg : fp.maxSegments,
                      store ? RAY_TO_LIST : RAY_TO_CACHE, store && fp.segments != 0ul, base, wr,
                      fragments, st);
    if (!store) {
      nseg = n;
      SmUints(fp.segCounts).v[pixel] = nseg;
    }
  }
  if (store) {
    dcEnd(wr, fp.fragCounts, pixel);
    return;  // counted in the count pass already: a retraced pixel's statistics are dropped
  }
  SM_FLUSH(SmStats(fp.stats).s.cacheRetraces, nseg > fp.segCacheK ? 1u : 0u);
  flushStats(fp, st, nseg, fragments, 0u);
}
