#version 460
// Exclusive prefix sum, level 1: each workgroup scans a block of 1024 uints in place and writes the
// block's total to sums[block]. Levels above scan the block totals; scan_add.comp adds them back.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require

layout(local_size_x = 256) in;
layout(buffer_reference, scalar) buffer Uints { uint v[]; };
layout(push_constant, scalar) uniform Push {
  uint64_t values;  // n uints, scanned in place
  uint64_t sums;    // one per block
  uint n;
} pc;

shared uint subgroupTotals[256];

void main() {
  Uints values = Uints(pc.values);
  uint base = gl_WorkGroupID.x * 1024u + gl_LocalInvocationIndex * 4u;
  uint a[4];
  uint local = 0u;
  for (uint i = 0u; i < 4u; ++i) {
    a[i] = base + i < pc.n ? values.v[base + i] : 0u;
    local += a[i];
  }
  uint excl = subgroupExclusiveAdd(local);
  if (gl_SubgroupInvocationID == gl_SubgroupSize - 1u) subgroupTotals[gl_SubgroupID] = excl + local;
  barrier();
  if (gl_LocalInvocationIndex == 0u) {
    uint run = 0u;
    for (uint s = 0u; s < gl_NumSubgroups; ++s) {
      uint t = subgroupTotals[s];
      subgroupTotals[s] = run;
      run += t;
    }
    Uints(pc.sums).v[gl_WorkGroupID.x] = run;
  }
  barrier();
  uint prefix = subgroupTotals[gl_SubgroupID] + excl;
  for (uint i = 0u; i < 4u; ++i) {
    if (base + i < pc.n) values.v[base + i] = prefix;
    prefix += a[i];
  }
}
