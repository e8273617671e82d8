#version 460
// Single-pass rendering with fixed-length fragment lists: traversal and marching fused, K slots per
// pixel, overflow dropped or merged (the paper's single-pass device interface).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
#include "ray_loop.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { uint64_t params; } pc;

void main() {
  FrameParams fp = SmParams(pc.params).p;
  uvec2 px = tiledPixel();
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
