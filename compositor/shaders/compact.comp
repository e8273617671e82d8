#version 460
// Step 1 of deep compositing: copies each pixel's list from the renderer's storage to its place in
// the contiguous send buffer, ordered by exchange position (dstOffsets = exclusive prefix sum of
// the counts in that order; exchange_types.h). Fragments are copied in their stored encoding.
#extension GL_GOOGLE_include_directive : require
#include "dc_common.glsl"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { DcCompactPush pc; };

void main() {
  uint p = smInvocationIndex(gl_WorkGroupSize.x);
  if (p >= pc.pixels) return;
  uint q = pc.interleaved != 0u ? dcInterleavedPosition(p, pc.ranks, pc.byRanks, pc.base, pc.extra) : p;
  uint n = DcUints(pc.counts).v[p];
  uint from = dcListBase(pc.srcOffsets, pc.fixedK, p);
  uint to = DcUints(pc.dstOffsets).v[q];
  for (uint i = 0u; i < n; ++i) {
    if (kDcEncoding == DC_ENCODING_FLOAT) {
      DcFloatFragments(pc.dst).v[to + i] = DcFloatFragments(pc.src).v[from + i];
    } else {
      DcPackedFragments(pc.dst).v[to + i] = DcPackedFragments(pc.src).v[from + i];
    }
  }
}
