#version 460
// Writes fragment lists produced on the host through the device interface (fragment_list.glsl)
// exactly as a renderer's shader does: one invocation per pixel, fragments in visibility order,
// zero-opacity ones dropped, fixed-length overflow dropped or merged.
#extension GL_GOOGLE_include_directive : require
#include "dc_common.glsl"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { DcWritePush pc; };

void main() {
  uint p = smInvocationIndex(gl_WorkGroupSize.x);
  if (p >= pc.pixels) return;
  uint n = DcUints(pc.rawCounts).v[p];
  if (pc.countOnly != 0u) {
    DcUints(pc.capacities).v[p] = n;
    return;
  }
  uint from = DcUints(pc.rawOffsets).v[p];
  DcListWriter w = kDcMode == DC_TWO_PASS
                       ? dcBegin(pc.fragments, DcUints(pc.offsets).v[p], DcUints(pc.capacities).v[p])
                       : dcBegin(pc.fragments, p * pc.fixedK, pc.fixedK);
  for (uint i = 0u; i < n; ++i) dcWrite(w, DcFloatFragments(pc.raw).v[from + i]);
  dcEnd(w, pc.counts, p);
}
