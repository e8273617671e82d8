#version 460
// Per-rank list statistics in one pass over the counts: the longest list (which picks the counter
// encoding), the non-empty pixels and the fragments. One atomic per subgroup.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
#include "dc_common.glsl"

layout(local_size_x = 256) in;
layout(push_constant, scalar) uniform Push { DcStatsPush pc; };

void main() {
  uint p = gl_GlobalInvocationID.x;
  uint n = p < pc.pixels ? DcUints(pc.counts).v[p] : 0u;
  uint longest = subgroupMax(n);
  uint nonEmpty = subgroupAdd(n > 0u ? 1u : 0u);
  uint fragments = subgroupAdd(n);
  if (subgroupElect()) {
    DcUint3 r = DcUint3(pc.result);
    if (longest > 0u) atomicMax(r.v[0], longest);
    if (nonEmpty > 0u) atomicAdd(r.v[1], nonEmpty);
    if (fragments > 0u) atomicAdd(r.v[2], fragments);
  }
}
