#version 460
// Step 1 with interleaved ownership: this rank's per-pixel counts in exchange-position order
// (exchange_types.h), so that the prefix sum, the packed counters and the send buffer give each
// destination a contiguous share. Each invocation moves kPixelsPerInvocation counts, consecutive
// invocations consecutive pixels in each round: a workgroup per 64 pixels made this pass cost
// lavapipe about 10 ms at 1024² (two ranks on two cores), mostly per-workgroup overhead.
#extension GL_GOOGLE_include_directive : require
#include "dc_common.glsl"

const uint kPixelsPerInvocation = 16u;  // deep_exchange.cpp dispatches accordingly

layout(local_size_x = 256) in;
layout(push_constant, scalar) uniform Push { DcPermutePush pc; };

void main() {
  uint first = smGroupIndex() * gl_WorkGroupSize.x * kPixelsPerInvocation + gl_LocalInvocationIndex;
  for (uint i = 0u; i < kPixelsPerInvocation; ++i) {
    uint p = first + i * gl_WorkGroupSize.x;
    if (p >= pc.pixels) return;
    DcUints(pc.dst).v[dcInterleavedPosition(p, pc.ranks, pc.byRanks, pc.base, pc.extra)] =
        DcUints(pc.src).v[p];
  }
}
