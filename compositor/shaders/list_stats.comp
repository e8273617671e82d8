#version 460
// Per-rank list statistics in one pass over the counts: the longest list (which picks the counter
// encoding), the non-empty pixels and the fragments. Each invocation sums kPixelsPerInvocation
// pixels, and a workgroup makes one atomic per total: one atomic per subgroup (131 072 per total at
// 1024² on lavapipe's 8-lane subgroups, from every core onto the same three words) made this pass
// cost about as much as compositing the image.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
#include "dc_common.glsl"

const uint kPixelsPerInvocation = 16u;  // list_statistics.cpp dispatches accordingly

layout(local_size_x = 256) in;
layout(push_constant, scalar) uniform Push { DcStatsPush pc; };

shared uint sLongest, sNonEmpty, sFragments;

void main() {
  if (gl_LocalInvocationIndex == 0u) {
    sLongest = 0u;
    sNonEmpty = 0u;
    sFragments = 0u;
  }
  barrier();
  uint longest = 0u, nonEmpty = 0u, fragments = 0u;
  // Consecutive invocations read consecutive counts in each round.
  uint first = smGroupIndex() * gl_WorkGroupSize.x * kPixelsPerInvocation + gl_LocalInvocationIndex;
  for (uint i = 0u; i < kPixelsPerInvocation; ++i) {
    uint p = first + i * gl_WorkGroupSize.x;
    uint n = p < pc.pixels ? DcUints(pc.counts).v[p] : 0u;
    longest = max(longest, n);
    nonEmpty += n > 0u ? 1u : 0u;
    fragments += n;
  }
  longest = subgroupMax(longest);
  nonEmpty = subgroupAdd(nonEmpty);
  fragments = subgroupAdd(fragments);
  if (subgroupElect()) {
    atomicMax(sLongest, longest);
    atomicAdd(sNonEmpty, nonEmpty);
    atomicAdd(sFragments, fragments);
  }
  barrier();
  if (gl_LocalInvocationIndex == 0u) {
    DcUint3 r = DcUint3(pc.result);
    if (sLongest > 0u) atomicMax(r.v[0], sLongest);
    if (sNonEmpty > 0u) atomicAdd(r.v[1], sNonEmpty);
    if (sFragments > 0u) atomicAdd(r.v[2], sFragments);
  }
}
