#version 460
// Exclusive prefix sum, level 1: each workgroup scans a block of 1024 uints in place and writes the
// block's total to sums[block]. Levels above scan the block totals; scan_add.comp adds them back.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require

#include "dispatch_grid.glsl"

layout(local_size_x = 256) in;
layout(buffer_reference, scalar) buffer Uints { uint v[]; };
layout(buffer_reference, scalar) buffer Uint64s { uint64_t v[]; };
layout(push_constant, scalar) uniform Push {
  uint64_t values;  // n uints, scanned in place
  uint64_t sums;    // one per block; the top level (one block): the 64-bit total
  uint n;
} pc;

shared uint subgroupTotals[256];
shared uint subgroupMaxima[256];

// A block's total over 1024 values cannot pass 32 bits while each value is below this.
const uint kNoWrapBelow = 1u << 22;

void main() {
  // The grid's last row may hold groups past the blocks; they would write past the block sums.
  uint block = smGroupIndex();
  if (block * 1024u >= pc.n) return;  // the whole workgroup: no barrier is left waiting
  Uints values = Uints(pc.values);
  uint base = block * 1024u + gl_LocalInvocationIndex * 4u;
  uint a[4];
  uint local = 0u;
  for (uint i = 0u; i < 4u; ++i) {
    a[i] = base + i < pc.n ? values.v[base + i] : 0u;
    local += a[i];
  }
  // The top level, one block, also sums in 64 bits: PrefixSum::downloadTotal refuses lists too
  // large for 32-bit indices by the true total, which the 32-bit one only gives mod 2^32. Below
  // it, a block total that would wrap is saturated instead (see below), so the top's sum passes
  // 2^32 - 1 too and is refused, never wrapped to a small total that undersizes the lists.
  const bool top = gl_NumWorkGroups.x * gl_NumWorkGroups.y == 1u;
  if (top && gl_LocalInvocationIndex == 0u) {
    uint64_t sum = 0ul;
    for (uint i = 0u; i < pc.n; ++i) sum += uint64_t(values.v[i]);
    Uint64s(pc.sums).v[0] = sum;
  }
  uint excl = subgroupExclusiveAdd(local);
  uint largest = subgroupMax(max(max(a[0], a[1]), max(a[2], a[3])));
  if (gl_SubgroupInvocationID == gl_SubgroupSize - 1u) {
    subgroupTotals[gl_SubgroupID] = excl + local;
    subgroupMaxima[gl_SubgroupID] = largest;
  }
  barrier();
  if (gl_LocalInvocationIndex == 0u) {
    uint run = 0u, blockMax = 0u;
    for (uint s = 0u; s < gl_NumSubgroups; ++s) {
      uint t = subgroupTotals[s];
      subgroupTotals[s] = run;
      run += t;
      blockMax = max(blockMax, subgroupMaxima[s]);
    }
    if (!top && blockMax >= kNoWrapBelow) {
      // Rare (a value of 4M or more: a pixel's count, or 1024 pixels' total): the block's total
      // again in 64 bits. Below 2^32 every partial sum of the block is exact too; above, the
      // total saturates and the offsets no longer matter, as the frame is refused.
      uint64_t sum = 0ul;
      uint end = min(block * 1024u + 1024u, pc.n);
      for (uint i = block * 1024u; i < end; ++i) sum += uint64_t(values.v[i]);
      run = sum > 0xFFFFFFFFul ? 0xFFFFFFFFu : uint(sum);
    }
    if (!top) Uints(pc.sums).v[block] = run;
  }
  barrier();
  uint prefix = subgroupTotals[gl_SubgroupID] + excl;
  for (uint i = 0u; i < 4u; ++i) {
    if (base + i < pc.n) values.v[base + i] = prefix;
    prefix += a[i];
  }
}
