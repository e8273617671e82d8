#version 460
// Single-pass rendering with fixed-length fragment lists: traversal and marching fused, K slots per
// pixel, overflow dropped or merged (the paper's single-pass device interface).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
#include "shell_query.glsl"
#include "segment.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { uint64_t params; } pc;

void main() {
  FrameParams fp = SmParams(pc.params).p;
  uvec2 px = gl_GlobalInvocationID.xy;
  bool inImage = px.x < fp.width && px.y < fp.height;
  SegmentStats st = noStats();
  uint nseg = 0u;
  DcListWriter wr = dcBegin(fp.fragments, 0u, 0u);
  if (inImage) {
    uint pixel = px.y * fp.width + px.x;
    RayFrame fr = pixelRay(fp, px);
    wr = dcBegin(fp.fragments, pixel * fp.fragK, fp.fragK);
    float prevEnd = 0.0, transmittance = 1.0;
    Traversal tr = beginTraversal(fp);
    Segment seg;
    while (nseg < fp.maxSegments && nextSegment(fr, fp.scene, tr, seg)) {
      nseg += 1u;
      DcFragment frag;
      if (integrateSegment(fr, fp, seg, prevEnd, frag, st)) {
        dcWrite(wr, frag);
        transmittance *= 1.0 - frag.color.a;
        if (1.0 - transmittance >= fp.earlyTermination) break;
      }
    }
    dcEnd(wr, fp.fragCounts, pixel);
  }
  flushStats(fp, st, nseg, wr.count, wr.overflow);
}
