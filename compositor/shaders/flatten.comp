#version 460
// Single-fragment compositing (what IceT-style compositors assume): each rank first composites its
// own list per pixel into one fragment whose depth is that of its first fragment. Wrong whenever a
// ray enters a rank's volume more than once with another rank in between; kept for comparison.
#extension GL_GOOGLE_include_directive : require
#include "dc_common.glsl"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { DcCompactPush pc; };

void main() {
  uint p = smInvocationIndex(gl_WorkGroupSize.x);
  if (p >= pc.pixels) return;
  uint n = DcUints(pc.counts).v[p];
  uint base = dcListBase(pc.srcOffsets, pc.fixedK, p);
  DcFragment acc;
  acc.color = vec4(0.0);
  acc.depth = 0.0;
  for (uint i = 0u; i < n; ++i) {
    DcFragment f = dcLoad(pc.src, base + i);
    if (i == 0u) acc.depth = f.depth;
    acc.color += (1.0 - acc.color.a) * f.color;
  }
  if (n > 0u) dcStore(pc.dst, p, acc);
  DcUints(pc.dstCounts).v[p] = min(n, 1u);
}
