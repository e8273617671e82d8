#include "render/tracer_pipeline.h"

#include "render_shaders.h"
#include "render_shaders_subgroups.h"
#include "vk/vk_error.h"

namespace sm::render {
namespace {

// Specialisation constant 20 of shell_hit.rint: the side its hit group finds.
constexpr uint32_t kSideConstant = 20;

vk::RayTracingPipelineDesc rayTracingDesc(const vk::Context& ctx, const GpuScene& scene,
                                          const std::string& name,
                                          std::vector<vk::SpecConstant> spec) {
  vk::RayTracingPipelineDesc d;
  d.name = name + " (ray tracing pipeline)";
  d.rayGen =
      ctx.rayTracingLimits().raygenSubgroups ? spv::tracer_rgen_subgroups() : spv::tracer_rgen();
  d.miss = spv::shell_miss_rmiss();
  if (scene.shellGeometry() == ShellGeometry::Boxes) {
    // crossing_pipeline.glsl: kEntryHitGroup, then kExitHitGroup.
    for (int32_t side : {-1, 1})
      d.hitGroups.push_back(
          {spv::shell_hit_rint(), spv::shell_hit_rahit(), {}, {{kSideConstant, uint32_t(side)}}});
  } else {
    d.hitGroups.push_back({{}, {}, spv::shell_hit_rchit(), {}});
  }
  d.specialization = std::move(spec);
  d.pushConstantBytes = sizeof(TracerPush);
  return d;
}

}  // namespace

TracerPipeline::TracerPipeline(const vk::Context& ctx, const GpuScene& scene, vk::Tracer tracer,
                               const std::string& name, std::vector<vk::SpecConstant> spec)
    : tracer_(tracer) {
  if (tracer == vk::Tracer::Pipeline) {
    rayTracing_ = vk::RayTracingPipeline(ctx, rayTracingDesc(ctx, scene, name, std::move(spec)));
    rayTracing_.setAccelerationStructure(scene.tlas());
    maxInvocations_ = ctx.rayTracingLimits().maxInvocations;
    return;
  }
  if (tracer != vk::Tracer::Query || !ctx.hasRayQuery())
    throw vk::VulkanError(name + ": " + ctx.deviceName() + " has no ray queries enabled",
                          VK_ERROR_FEATURE_NOT_PRESENT);
  compute_ = vk::ComputePipeline(
      ctx, {name, spv::tracer(), std::move(spec), uint32_t(sizeof(TracerPush)), true});
  compute_.setAccelerationStructure(scene.tlas());
}

void TracerPipeline::record(VkCommandBuffer cmd, VkDeviceAddress params, int width, int height,
                            uint32_t store) const {
  const TracerPush push{params, store};
  const uint32_t tilesX = vk::groupsFor(uint64_t(width), 8),
                 tilesY = vk::groupsFor(uint64_t(height), 8);
  if (tracer_ == vk::Tracer::Query) {
    compute_.dispatch(cmd, tilesX, tilesY, 1, push);
    return;
  }
  // stage_raygen.glsl: 64 launch ids along x per 8 x 8 tile.
  const uint64_t invocations = uint64_t(tilesX) * 64 * tilesY;
  if (invocations > maxInvocations_)
    throw vk::VulkanError("a " + std::to_string(width) + " x " + std::to_string(height) +
                              " image needs " + std::to_string(invocations) +
                              " ray generation invocations, more than the device's " +
                              std::to_string(maxInvocations_) + " per trace",
                          VK_ERROR_FEATURE_NOT_PRESENT);
  rayTracing_.trace(cmd, tilesX * 64, tilesY, push);
}

}  // namespace sm::render
