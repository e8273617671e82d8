#version 460
// The tracer's passes (tracer_passes.glsl) with ray queries from a compute shader.
#extension GL_GOOGLE_include_directive : require
#include "stage_compute.glsl"
#include "scene_access.glsl"
#include "subgroup_ops.glsl"
#include "counters.glsl"
#include "ray_frame.glsl"
#include "interpolate.glsl"
#include "walk_state.glsl"
#include "transfer.glsl"
#include "element_step.glsl"
#include "march.glsl"
#include "fragment_list.glsl"
#include "shell_hit.glsl"
#include "shell_crossing.glsl"
#include "crossing_query.glsl"
#include "shell_entry.glsl"
#include "shell_query.glsl"
#include "segment.glsl"
#include "ray_loop.glsl"
#include "tracer_passes.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push {
  uint64_t params;
  uint store;  // two-pass passes: 0 count, 1 store
} pc;

void main() { tracePixel(SmParams(pc.params).p, smPixel(), pc.store != 0u); }
