#version 460
// Counts every invocation of a one-dimensional dispatch laid out in rows (dispatchItems): once per
// item, and those past the items in one extra counter.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "dispatch_grid.glsl"

layout(local_size_x = 2) in;
layout(buffer_reference, scalar) buffer Uints { uint v[]; };
layout(push_constant, scalar) uniform Push {
  uint64_t hits;  // n + 1 counters
  uint n;
} pc;

void main() {
  uint i = smInvocationIndex(gl_WorkGroupSize.x);
  atomicAdd(Uints(pc.hits).v[min(i, pc.n)], 1u);
}
