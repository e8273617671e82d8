#version 460
// Step 2, before the exchange: packs the 32-bit per-pixel counts into 2-, 4- or 8-bit counters.
// Each destination's counters start on a word of their own, so that its share is contiguous and
// can be sent without the neighbours' bits. One invocation writes one word: no atomics.
#extension GL_GOOGLE_include_directive : require
#include "dc_common.glsl"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { DcEncodePush pc; };

// The destination whose words contain w: the last d with segments[d].word <= w (empty
// destinations share their word start with the next one and are skipped).
uint destinationOf(uint w) {
  uint lo = 0u, hi = pc.ranks;  // invariant: word(lo) <= w < word(hi)
  while (hi - lo > 1u) {
    uint mid = (lo + hi) / 2u;
    if (DcUints(pc.segments).v[2u * mid + 1u] <= w) lo = mid; else hi = mid;
  }
  return lo;
}

void main() {
  uint w = smInvocationIndex(gl_WorkGroupSize.x);
  if (w >= pc.totalWords) return;
  uint d = destinationOf(w);
  uint firstPixel = DcUints(pc.segments).v[2u * d];
  uint endPixel = DcUints(pc.segments).v[2u * d + 2u];
  uint perWord = 32u / pc.bits;
  uint first = firstPixel + (w - DcUints(pc.segments).v[2u * d + 1u]) * perWord;
  uint packed = 0u;
  for (uint k = 0u; k < perWord; ++k) {
    uint p = first + k;
    if (p < endPixel) packed |= DcUints(pc.counts).v[p] << (k * pc.bits);
  }
  DcUints(pc.words).v[w] = packed;
}
