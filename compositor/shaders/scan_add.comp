#version 460
// Exclusive prefix sum, down-sweep: adds each block's scanned offset to its 1024 values.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require

#include "dispatch_grid.glsl"

layout(local_size_x = 256) in;
layout(buffer_reference, scalar) buffer Uints { uint v[]; };
layout(push_constant, scalar) uniform Push {
  uint64_t values;
  uint64_t sums;  // scanned block offsets
  uint n;
} pc;

void main() {
  uint block = smGroupIndex();
  if (block * 1024u >= pc.n) return;  // past the blocks, in the grid's last row
  uint add = Uints(pc.sums).v[block];
  uint base = block * 1024u + gl_LocalInvocationIndex * 4u;
  for (uint i = 0u; i < 4u; ++i)
    if (base + i < pc.n) Uints(pc.values).v[base + i] += add;
}
