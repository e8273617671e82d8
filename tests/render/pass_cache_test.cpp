// Renderers of one scene share their pipelines (render::PassCache): a renderer for another image
// size builds none and renders what a renderer of its own renders; one whose lists need other
// specialisation constants gets pipelines of its own.
#include <gtest/gtest.h>

#include "render_harness.h"
#include "test_meshes.h"

namespace sm::render {
namespace {

using test::cubeView;

TEST(PassCache, ARendererOfAnotherSizeTakesThePipelinesOver) {
  auto m = ref::test::cubeMesh(ref::test::Split::Wedges, 3);
  auto f = ref::test::pointField(m, [](const glm::dvec3& p) { return p.x + 2 * p.y + 3 * p.z; });
  test::RenderRig rig(m, f, 48, 32);
  rig.renderer.render(cubeView(48, 32));
  const std::shared_ptr<PassCache> passes = rig.renderer.passes();
  const uint64_t built = passes->pipelinesBuilt();
  EXPECT_GT(built, 0u);

  comp::DeepCompositor other(rig.ctx, nullptr, 40, 30, {});
  Renderer shared(rig.ctx, rig.scene, other, passes);
  EXPECT_EQ(shared.passes(), passes);
  const FrameResult a = shared.render(cubeView(40, 30));
  EXPECT_EQ(passes->pipelinesBuilt(), built);  // nothing compiled for the new size

  comp::DeepCompositor third(rig.ctx, nullptr, 40, 30, {});
  Renderer own(rig.ctx, rig.scene, third);
  const FrameResult b = own.render(cubeView(40, 30));
  EXPECT_NE(own.passes(), passes);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  EXPECT_EQ(a.pixels, b.pixels);  // the same pipelines' work, bit for bit

  // Fixed-length lists specialise the tracer otherwise: not served by the two-pass cache.
  comp::CompositorOptions fixed;
  fixed.mode = comp::ListMode::FixedDrop;
  fixed.fixedK = 4;
  comp::DeepCompositor lists(rig.ctx, nullptr, 40, 30, fixed);
  Renderer separate(rig.ctx, rig.scene, lists, passes);
  EXPECT_NE(separate.passes(), passes);
  separate.render(cubeView(40, 30));
  EXPECT_EQ(passes->pipelinesBuilt(), built);
  EXPECT_EQ(rig.ctx.validationErrors(), 0u);
}

}  // namespace
}  // namespace sm::render
