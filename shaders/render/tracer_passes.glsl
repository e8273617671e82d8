// The tracer's passes, one function a pixel each, for both entry points (tracer.comp with ray
// queries, tracer.rgen with a ray tracing pipeline). kPass picks one when the pipeline is built, so
// a pipeline holds one pass's code.
//
// Two-pass lists (render_passes.h, CountStorePass):
//   PASS_TRAVERSE: the stage-split tracer's traversal. Count mode writes how many segments the
//     pixel's ray has; store mode writes them at the offsets the prefix sum of the counts gave.
//   PASS_CACHED: traversal and marching with one trace. Count mode traces and marches each pixel's
//     ray, keeps the first segCacheK segments with their fragments in the pixel's cache slots,
//     writes the segment count (the list's capacity) and counts the pixels with more segments than
//     slots. Store mode, after the prefix sum: store_cached.comp copies the cached fragments (and
//     segments, if kept) to the pixel's place in the lists; this pass, dispatched only when some
//     pixel has more segments than slots, traces those pixels' rays again (the same code on the
//     same data gives the same segments and fragments).
//   Count or store is a push constant, not a specialisation: one pipeline for both, because the
//   tracer is most of the shader and each copy costs lavapipe about two seconds to compile when a
//   renderer is first used. For the same reason each pass has one call site of traceRay.
// Fixed-K lists:
//   PASS_FUSED: traversal and marching in one pass, K slots per pixel, overflow dropped or merged
//     (the paper's single-pass device interface).
#ifndef SM_TRACER_PASSES_GLSL
#define SM_TRACER_PASSES_GLSL

const uint PASS_TRAVERSE = 0u;
const uint PASS_CACHED = 1u;
const uint PASS_FUSED = 2u;
layout(constant_id = 30) const uint kPass = PASS_CACHED;

void traversePixel(FrameParams fp, uvec2 px, bool store) {
  if (px.x >= fp.width || px.y >= fp.height) return;
  uint pixel = px.y * fp.width + px.x;
  RayFrame fr = pixelRay(fp, px);
  uint base = store ? SmUints(fp.segOffsets).v[pixel] : 0u;
  uint cap = store ? SmUints(fp.segCounts).v[pixel] : fp.maxSegments;
  uint n = 0u;
  Traversal tr = beginTraversal(fp);
  Segment seg;
  while (n < cap && nextSegment(fr, fp.scene, tr, 0.0, seg)) {
    if (store) SmSegments(fp.segments).v[base + n] = seg;
    n += 1u;
  }
  if (store) return;
  SmUints(fp.segCounts).v[pixel] = n;
  SM_FLUSH(SmStats(fp.stats).s.shellQueries, tr.queries);
}

void renderCachedPixel(FrameParams fp, uvec2 px, bool store) {
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

void renderFusedPixel(FrameParams fp, uvec2 px) {
  bool inImage = px.x < fp.width && px.y < fp.height;
  SegmentStats st = noStats();
  uint nseg = 0u, fragments = 0u;
  DcListWriter wr = dcBegin(fp.fragments, 0u, 0u);
  if (inImage) {
    uint pixel = px.y * fp.width + px.x;
    wr = dcBegin(fp.fragments, pixel * fp.fragK, fp.fragK);
    nseg = traceRay(pixelRay(fp, px), fp, pixel, fp.maxSegments, RAY_TO_LIST, false, 0u, wr, fragments, st);
    dcEnd(wr, fp.fragCounts, pixel);
  }
  flushStats(fp, st, nseg, wr.count, wr.overflow);
}

void tracePixel(FrameParams fp, uvec2 px, bool store) {
  if (kPass == PASS_TRAVERSE) traversePixel(fp, px, store);
  else if (kPass == PASS_CACHED) renderCachedPixel(fp, px, store);
  else renderFusedPixel(fp, px);
}

#endif
