#version 460
// Composites each pixel's list front to back into the image (one rank: no exchange). Lists are in
// visibility order already: one invocation wrote each pixel's fragments in ray order.
#extension GL_GOOGLE_include_directive : require
#include "dc_common.glsl"

layout(local_size_x = 64) in;
layout(buffer_reference, scalar) buffer DcImage { vec4 v[]; };
layout(push_constant, scalar) uniform Push { DcLocalPush pc; };

void main() {
  uint p = smInvocationIndex(gl_WorkGroupSize.x);
  if (p >= pc.pixels) return;
  uint n = DcUints(pc.counts).v[p];
  uint base = dcListBase(pc.offsets, pc.fixedK, p);
  vec4 acc = vec4(0.0);
  for (uint i = 0u; i < n; ++i) acc += (1.0 - acc.a) * dcLoad(pc.fragments, base + i).color;
  DcImage(pc.image).v[p] = acc;
}
