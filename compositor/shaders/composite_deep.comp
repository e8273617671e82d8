#version 460
// Step 4 of deep compositing: each pixel of this rank's range has one list from every rank, each in
// visibility order. A k-way merge by depth composites them front to back; equal depths go in rank
// order and, within a rank, in list order, so the result is deterministic and equals a sort of the
// union by (depth, rank, index).
//
// Up to kRegisterLists non-empty lists are merged with their heads in registers. A pixel with more
// non-empty lists merges with its cursors in the offsets/counts buffers themselves (each pixel owns
// its entries there), scanning all ranks per fragment: slower, but bounded by nothing.
#extension GL_GOOGLE_include_directive : require
#include "dc_common.glsl"

layout(local_size_x = 64) in;
layout(constant_id = 0) const uint kRegisterLists = 8u;
layout(push_constant, scalar) uniform Push { DcDeepPush pc; };
layout(buffer_reference, scalar) buffer DcImage { vec4 v[]; };

vec4 over(vec4 acc, vec4 c) { return acc + (1.0 - acc.a) * c; }

vec4 mergeInRegisters(uint j) {
  uint cursor[kRegisterLists], end[kRegisterLists];
  DcFragment head[kRegisterLists];
  uint live = 0u;
  for (uint s = 0u; s < pc.ranks; ++s) {
    uint n = DcUints(pc.counts).v[s * pc.pixels + j];
    if (n == 0u) continue;
    uint at = DcUints(pc.offsets).v[s * pc.pixels + j];
    cursor[live] = at;
    end[live] = at + n;
    head[live] = dcLoad(pc.fragments, at);
    live += 1u;
  }
  vec4 acc = vec4(0.0);
  while (live > 0u) {
    uint best = 0u;
    for (uint a = 1u; a < live; ++a)
      if (head[a].depth < head[best].depth) best = a;
    acc = over(acc, head[best].color);
    cursor[best] += 1u;
    if (cursor[best] < end[best]) {
      head[best] = dcLoad(pc.fragments, cursor[best]);
    } else {  // drop the finished list, keeping rank order for ties
      live -= 1u;
      for (uint a = best; a < live; ++a) {
        cursor[a] = cursor[a + 1u];
        end[a] = end[a + 1u];
        head[a] = head[a + 1u];
      }
    }
  }
  return acc;
}

vec4 mergeInMemory(uint j) {
  vec4 acc = vec4(0.0);
  for (;;) {
    uint best = 0xffffffffu;
    float bestDepth = 0.0;
    for (uint s = 0u; s < pc.ranks; ++s) {
      uint i = s * pc.pixels + j;
      if (DcUints(pc.counts).v[i] == 0u) continue;
      float d = dcLoad(pc.fragments, DcUints(pc.offsets).v[i]).depth;
      if (best == 0xffffffffu || d < bestDepth) {
        best = i;
        bestDepth = d;
      }
    }
    if (best == 0xffffffffu) return acc;
    uint at = DcUints(pc.offsets).v[best];
    acc = over(acc, dcLoad(pc.fragments, at).color);
    DcUints(pc.offsets).v[best] = at + 1u;
    DcUints(pc.counts).v[best] -= 1u;
  }
  return acc;
}

void main() {
  uint j = smInvocationIndex(gl_WorkGroupSize.x);
  if (j >= pc.pixels) return;
  uint lists = 0u;
  for (uint s = 0u; s < pc.ranks; ++s)
    if (DcUints(pc.counts).v[s * pc.pixels + j] != 0u) lists += 1u;
  DcImage(pc.image).v[j] = lists <= kRegisterLists ? mergeInRegisters(j) : mergeInMemory(j);
}
