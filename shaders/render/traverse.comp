#version 460
// Shell traversal pass: per pixel, the segments of this rank's volume along the pixel's ray.
// Count mode writes how many (two-pass lists, first pass); store mode writes them at the offsets
// the prefix sum of the counts gave.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
#include "shell_query.glsl"
#include "segment.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push {
  uint64_t params;
  uint store;  // 0: count pass, 1: store pass (one pipeline for both: render_cached.comp says why)
} pc;

void main() {
  FrameParams fp = SmParams(pc.params).p;
  bool store = pc.store != 0u;
  uvec2 px = tiledPixel();
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
