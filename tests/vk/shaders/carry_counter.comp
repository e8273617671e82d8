#version 460
// Every invocation adds `add` to a 64-bit counter kept as two 32-bit words (counters.glsl).
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "counters.glsl"

layout(local_size_x = 64) in;
layout(buffer_reference, scalar) buffer Counter { uint lo, hi; };
layout(push_constant, scalar) uniform Push {
  uint64_t counter;
  uint add;
} pc;

void main() {
  Counter c = Counter(pc.counter);
  SM_ADD_WITH_CARRY(c.lo, c.hi, pc.add);
}
