// What the tracer library takes from a ray generation stage (stage_compute.glsl gives the same for
// compute). Launches are (64 x tiles across, tiles down): each run of 64 launch ids along x is one
// 8 x 8 tile, walked in the same order as a compute workgroup, so that neighbouring invocations
// trace neighbouring rays on either stage.
//
// Subgroup operations only where the device offers them in ray generation shaders (NVIDIA does,
// lavapipe does not): the build compiles this stage twice, with and without SM_RAYGEN_SUBGROUPS,
// and the renderer picks by subgroupSupportedStages. Without them every reduction and vote in
// subgroup_ops.glsl falls back to the invocation's own value, which gives the same results.
#ifndef SM_STAGE_GLSL
#define SM_STAGE_GLSL

#extension GL_EXT_ray_tracing : require
#ifdef SM_RAYGEN_SUBGROUPS
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#define SM_SUBGROUPS 1
#else
#define SM_SUBGROUPS 0
#endif

void smTileAndLane(out uvec2 tile, out uint lane) {
  tile = uvec2(gl_LaunchIDEXT.x >> 6u, gl_LaunchIDEXT.y);
  lane = gl_LaunchIDEXT.x & 63u;
}

#endif
