#version 460
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
layout(local_size_x = 64) in;
layout(buffer_reference, scalar) buffer Floats { float v[]; };
layout(push_constant, scalar) uniform Push { uint64_t data; uint n; float factor; } pc;
layout(constant_id = 0) const uint kAdd = 0;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.n) return;
  Floats f = Floats(pc.data);
  f.v[i] = f.v[i] * pc.factor + float(kAdd);
}
