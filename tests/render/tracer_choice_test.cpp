// Choosing the tracer: auto takes ray queries where the device offers them and the ray tracing
// pipeline where it does not (a capability mask hides ray queries from lavapipe, which has both),
// with the same image; a device without the tracer asked for, or without either, is refused with
// a message naming the device and what it lacks. Every image test of the harness also renders with
// both tracers and compares them bit for bit (render_harness.h, expectOtherTracerAgrees).
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <string>

#include "render_harness.h"
#include "test_meshes.h"
#include "vk/vk_error.h"

namespace sm::render {
namespace {

// Sampled, so that the cases below cover both integrations (one asks for element-exact).
RenderSettings wedgeView() {
  RenderSettings s = test::cubeView(40, 30);
  s.integration = Integration::Sampled;
  return s;
}

struct Scene {
  mesh::UnstructuredMesh mesh = ref::test::cubeMesh(ref::test::Split::Wedges, 3);
  std::vector<float> values =
      ref::test::pointField(mesh, [](const glm::dvec3& p) { return p.x + 2 * p.y + 3 * p.z; });
};

std::string refusal(const vk::ContextOptions& o) {
  try {
    vk::Context ctx(o);
  } catch (const vk::VulkanError& e) {
    return e.what();
  }
  return "";
}

TEST(TracerChoice, AutoTakesRayQueriesWhereTheDeviceOffersThem) {
  vk::Context ctx;
  if (!ctx.hasRayQuery()) GTEST_SKIP() << ctx.deviceName() << " has no ray queries";
  EXPECT_EQ(ctx.tracer(), vk::Tracer::Query);
}

TEST(TracerChoice, AutoTakesThePipelineWhereRayQueriesAreMissingAndTheImageIsTheSame) {
  Scene sc;
  test::RenderRig withQueries(sc.mesh, sc.values, 40, 30);
  if (!withQueries.ctx.hasRayQuery() || !withQueries.ctx.hasRayTracingPipeline())
    GTEST_SKIP() << withQueries.ctx.deviceName() << " does not offer both tracers";
  test::GpuRenderOptions masked;
  masked.context.hide = vk::kHideRayQuery;
  test::RenderRig withoutQueries(sc.mesh, sc.values, 40, 30, masked);
  EXPECT_FALSE(withoutQueries.ctx.hasRayQuery());
  EXPECT_EQ(withoutQueries.ctx.tracer(), vk::Tracer::Pipeline);
  EXPECT_EQ(withoutQueries.renderer.tracer(), vk::Tracer::Pipeline);
  EXPECT_EQ(withQueries.renderer.tracer(), vk::Tracer::Query);
  const FrameResult a = withQueries.renderer.render(wedgeView());
  const FrameResult b = withoutQueries.renderer.render(wedgeView());
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec4)), 0);
  EXPECT_GT(a.counters.segments, 0u);
  EXPECT_EQ(std::memcmp(&a.counters, &b.counters, sizeof(a.counters)), 0);
  EXPECT_EQ(withQueries.ctx.validationErrors() + withoutQueries.ctx.validationErrors(), 0u);
}

TEST(TracerChoice, TheRayGenerationFallbackWithoutSubgroupsRendersTheSameImage) {
  // Devices with subgroup operations in ray generation shaders (NVIDIA's) run the subgroup
  // variant; hiding them runs the fallback (stage_raygen.glsl). On lavapipe both are the fallback.
  Scene sc;
  test::GpuRenderOptions pipeline;
  pipeline.context.tracer = vk::Tracer::Pipeline;
  test::RenderRig a(sc.mesh, sc.values, 40, 30, pipeline);
  pipeline.context.hide = vk::kHideRaygenSubgroups;
  test::RenderRig b(sc.mesh, sc.values, 40, 30, pipeline);
  EXPECT_FALSE(b.ctx.rayTracingLimits().raygenSubgroups);
  const FrameResult fa = a.renderer.render(wedgeView());
  const FrameResult fb = b.renderer.render(wedgeView());
  EXPECT_EQ(std::memcmp(fa.pixels.data(), fb.pixels.data(), fa.pixels.size() * sizeof(glm::vec4)),
            0);
  EXPECT_EQ(std::memcmp(&fa.counters, &fb.counters, sizeof(fa.counters)), 0);
}

// Every frame strategy and list mode with both tracers, compared bit for bit:
// cached and stage-split two-pass lists, fixed lists with drop and merge, 8-bit fragments,
// element-exact integration, and device-triangle shells (the closest-hit shader).
TEST(TracerChoice, EveryFrameStrategyAndListModeIsTheSameWithBothTracers) {
  Scene sc;
  struct Case {
    const char* name;
    std::function<void(RenderSettings&, test::GpuRenderOptions&)> set;
  };
  const std::vector<Case> cases = {
      {"cached two-pass", [](RenderSettings&, test::GpuRenderOptions&) {}},
      {"stage-split two-pass",
       [](RenderSettings& s, test::GpuRenderOptions&) { s.segmentCacheBytes = 0; }},
      {"fixed drop",
       [](RenderSettings&, test::GpuRenderOptions& o) {
         o.lists.mode = comp::ListMode::FixedDrop;
         o.lists.fixedK = 2;
       }},
      {"fixed merge, rgba8",
       [](RenderSettings&, test::GpuRenderOptions& o) {
         o.lists.mode = comp::ListMode::FixedMerge;
         o.lists.fixedK = 2;
         o.lists.encoding = comp::Encoding::Rgba8;
       }},
      {"element-exact", [](RenderSettings& s,
                           test::GpuRenderOptions&) { s.integration = Integration::ElementExact; }},
      {"device triangles",
       [](RenderSettings&, test::GpuRenderOptions& o) { o.shell = ShellGeometry::Triangles; }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    RenderSettings s = wedgeView();
    test::GpuRenderOptions o;
    c.set(s, o);
    test::RenderRig rig(sc.mesh, sc.values, s.width, s.height, o);
    const FrameResult frame = rig.renderer.render(s);
    test::expectOtherTracerAgrees(rig.ctx, rig.scene, rig.compositor, s, rig.renderer, frame);
    EXPECT_GT(frame.counters.segments, 0u);
    EXPECT_EQ(rig.ctx.validationErrors(), 0u);
  }
}

TEST(TracerChoice, AskingForAMissingTracerNamesTheDeviceAndWhatItLacks) {
  vk::Context plain;
  vk::ContextOptions o;
  o.tracer = vk::Tracer::Query;
  o.hide = vk::kHideRayQuery;
  const std::string query = refusal(o);
  EXPECT_NE(query.find("for the query tracer"), std::string::npos) << query;
  EXPECT_NE(query.find(plain.deviceName()), std::string::npos) << query;
  EXPECT_NE(query.find("lacks ray queries (VK_KHR_ray_query"), std::string::npos) << query;
  EXPECT_EQ(query.find('\n'), std::string::npos) << query;

  o.tracer = vk::Tracer::Pipeline;
  o.hide = vk::kHideRayTracingPipeline;
  const std::string pipeline = refusal(o);
  EXPECT_NE(pipeline.find("lacks a ray tracing pipeline (VK_KHR_ray_tracing_pipeline"),
            std::string::npos)
      << pipeline;
}

TEST(TracerChoice, ADeviceWithNeitherTracerIsRefusedNamingBoth) {
  vk::ContextOptions o;
  o.hide = vk::kHideRayQuery | vk::kHideRayTracingPipeline;
  const std::string both = refusal(o);
  EXPECT_NE(both.find("no Vulkan device has what shellmarch needs"), std::string::npos) << both;
  EXPECT_NE(both.find("lacks ray queries (VK_KHR_ray_query"), std::string::npos) << both;
  EXPECT_NE(both.find("and a ray tracing pipeline (VK_KHR_ray_tracing_pipeline"), std::string::npos)
      << both;
  // The compositor alone needs neither.
  o.rayTracing = false;
  EXPECT_EQ(refusal(o), "");
}

TEST(TracerChoice, TracerNamesParseAndBadOnesAreRefused) {
  EXPECT_EQ(vk::parseTracer("--tracer", "auto"), vk::Tracer::Auto);
  EXPECT_EQ(vk::parseTracer("--tracer", "query"), vk::Tracer::Query);
  EXPECT_EQ(vk::parseTracer("--tracer", "pipeline"), vk::Tracer::Pipeline);
  try {
    vk::parseTracer("--tracer", "rtx");
    ADD_FAILURE() << "rtx accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "--tracer: 'rtx' is not auto, query or pipeline");
  }
}

}  // namespace
}  // namespace sm::render
