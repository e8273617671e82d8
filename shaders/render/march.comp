#version 460
// Marching pass: per pixel, integrate the segments traversal stored and write one fragment per
// segment into the pixel's list (two-pass lists: the list is exactly as long as the segments).
#extension GL_GOOGLE_include_directive : require
#include "stage_compute.glsl"
#include "scene_access.glsl"
#include "subgroup_ops.glsl"
#include "counters.glsl"
#include "ray_frame.glsl"
#include "interpolate.glsl"
#include "walk_state.glsl"
#include "transfer.glsl"
#include "element_step.glsl"
#include "march.glsl"
#include "fragment_list.glsl"
#include "shell_hit.glsl"
#include "shell_crossing.glsl"
#include "shell_entry.glsl"
#include "segment.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { uint64_t params; } pc;

void main() {
  FrameParams fp = SmParams(pc.params).p;
  uvec2 px = smPixel();
  bool inImage = px.x < fp.width && px.y < fp.height;
  SegmentStats st = noStats();
  uint nseg = 0u;
  DcListWriter wr = dcBegin(fp.fragments, 0u, 0u);
  if (inImage) {
    uint pixel = px.y * fp.width + px.x;
    RayFrame fr = pixelRay(fp, px);
    uint base = SmUints(fp.segOffsets).v[pixel];
    nseg = SmUints(fp.segCounts).v[pixel];
    wr = dcBegin(fp.fragments, base, nseg);
    float prevEnd = 0.0, transmittance = 1.0;
    for (uint i = 0u; i < nseg; ++i) {
      DcFragment frag;
      if (integrateSegment(fr, fp, SmSegments(fp.segments).v[base + i], prevEnd, frag, st)) {
        dcWrite(wr, frag);
        transmittance *= 1.0 - frag.color.a;
        // Later segments of this rank lie behind: nothing any rank adds between can make them
        // more visible than this rank's own transmittance allows.
        if (1.0 - transmittance >= fp.earlyTermination) break;
      }
    }
    dcEnd(wr, fp.fragCounts, pixel);
  }
  flushStats(fp, st, nseg, wr.count, wr.overflow);
}
