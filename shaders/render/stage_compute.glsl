// What the tracer library takes from a compute stage: where an invocation's pixel lies (8 x 8
// workgroups) and subgroup operations. stage_raygen.glsl gives the same for ray generation
// shaders. An entry point includes exactly one stage file, before the library.
#ifndef SM_STAGE_GLSL
#define SM_STAGE_GLSL

#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#define SM_SUBGROUPS 1

// The invocation's 8 x 8 tile of pixels and its place (0..63) in the tile.
void smTileAndLane(out uvec2 tile, out uint lane) {
  tile = gl_WorkGroupID.xy;
  lane = gl_LocalInvocationIndex;
}

#endif
