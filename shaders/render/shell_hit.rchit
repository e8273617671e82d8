#version 460
// Closest-hit shader of the pipeline tracer in device-triangle mode: the device's triangle test
// decided (culling picks the side); record the hit as the ray query's committed intersection.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "shell_hit.glsl"

layout(location = 0) rayPayloadInEXT ShellHit hit;

void main() {
  hit.tri = uint(gl_PrimitiveID);
  hit.tBest = gl_HitTEXT;
}
