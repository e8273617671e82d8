#version 460
// One ray per invocation along (0, 0, dz) from z = z0 at (x, y) = rays[i]; records the hit.
#extension GL_EXT_ray_query : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
layout(local_size_x = 8) in;
layout(set = 0, binding = 0) uniform accelerationStructureEXT tlas;
layout(buffer_reference, scalar) buffer Vec2s { vec2 v[]; };
layout(buffer_reference, scalar) buffer Hits { vec4 v[]; };  // t, primitive, front face, hit?
layout(push_constant, scalar) uniform Push { uint64_t rays; uint64_t hits; uint n; uint flags; float z0; float dz; } pc;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.n) return;
  vec2 xy = Vec2s(pc.rays).v[i];
  rayQueryEXT q;
  rayQueryInitializeEXT(q, tlas, pc.flags, 0xFF, vec3(xy, pc.z0), 0.0, vec3(0, 0, pc.dz), 10.0);
  while (rayQueryProceedEXT(q)) {}
  vec4 r = vec4(-1.0, -1.0, -1.0, 0.0);
  if (rayQueryGetIntersectionTypeEXT(q, true) == gl_RayQueryCommittedIntersectionTriangleEXT) {
    r = vec4(rayQueryGetIntersectionTEXT(q, true), float(rayQueryGetIntersectionPrimitiveIndexEXT(q, true)),
             rayQueryGetIntersectionFrontFaceEXT(q, true) ? 1.0 : 0.0, 1.0);
  }
  Hits(pc.hits).v[i] = r;
}
