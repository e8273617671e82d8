#version 460
// Store pass of the cached two-pass lists, for the pixels whose segments all fit in the cache: copy
// the cached fragments (and, with keepSegments, the segments) to the pixel's place in the lists;
// render_cached.comp traces the other pixels again. A pipeline of its own because running the
// tracer's pipeline only to copy cost about 10 ms of a 512² frame on lavapipe (40 ms at 1024²):
// every invocation paid for the tracer's stack frame whether it traced or not.
#extension GL_GOOGLE_include_directive : require
#include "scene_access.glsl"
#include "fragment_list.glsl"
#include "dispatch_grid.glsl"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { uint64_t params; } pc;

void main() {
  FrameParams fp = SmParams(pc.params).p;
  uint pixel = smInvocationIndex(gl_WorkGroupSize.x);
  if (pixel >= fp.width * fp.height) return;
  uint n = SmUints(fp.segCounts).v[pixel];
  if (n > fp.segCacheK) return;  // traced again by the tracer's store pass
  uint base = SmUints(fp.segOffsets).v[pixel];
  DcListWriter wr = dcBegin(fp.fragments, base, n);
  for (uint i = 0u; i < n; ++i) {
    CachedSegment c = SmCachedSegments(fp.segCache).v[pixel * fp.segCacheK + i];
    if (fp.segments != 0ul) SmSegments(fp.segments).v[base + i] = c.segment;  // keepSegments
    if (c.hasFragment != 0u) dcWrite(wr, DcFragment(c.color, c.depth));
  }
  dcEnd(wr, fp.fragCounts, pixel);
}
