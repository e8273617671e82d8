// session::RankSession: one rank's context, scene and a compositor and renderer per image size.
// Its frames are the frames of a renderer wired by hand; a new size compiles nothing; it keeps the
// sizes it is told to; releasing renderers starts cold; replacing the scene keeps the counts.
#include <gtest/gtest.h>

#include "common/error.h"
#include "prep/prepare.h"
#include "render/render_harness.h"
#include "session/rank_session.h"
#include "test_meshes.h"

namespace sm::session {
namespace {

using test::cubeView;

struct Cube {
  mesh::UnstructuredMesh mesh = ref::test::cubeMesh(ref::test::Split::Wedges, 3);
  std::vector<float> values =
      ref::test::pointField(mesh, [](const glm::dvec3& p) { return p.x + 2 * p.y + 3 * p.z; });
  prep::PreparedRank rank() const {
    mesh::UnstructuredMesh m = mesh;
    return prep::prepareRank(m, prep::makeGlobalFrame(mesh.bounds()), prep::PrepOptions{}).rank;
  }
  // The cube as `session`'s scene, its positions moved in; the rank is returned without them.
  prep::PreparedRank upload(RankSession& session) const {
    prep::PreparedRank r = rank();
    session.setScene(r, std::move(r.positions)).setScalars(prep::gatherScalars(r, values));
    return r;
  }
};

TEST(RankSession, FramesAreThoseOfARendererWiredByHand) {
  const Cube cube;
  RankSession session(vk::ContextOptions{}, nullptr);
  cube.upload(session);
  const render::FrameResult a = session.render(cubeView(48, 32));

  test::RenderRig rig(cube.mesh, cube.values, 48, 32);
  const render::FrameResult b = rig.renderer.render(cubeView(48, 32));
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_EQ(session.context().validationErrors(), 0u);
}

TEST(RankSession, ANewSizeCompilesNothingAndKeptSizesAreReused) {
  const Cube cube;
  RankSession session(vk::ContextOptions{}, nullptr, SessionOptions{{}, vk::Tracer::Auto, 2});
  EXPECT_TRUE(cube.upload(session).positions.empty());  // moved in: the host holds one copy
  session.render(cubeView(48, 32));
  const uint64_t built = session.pipelinesBuilt();
  EXPECT_GT(built, 0u);
  render::Renderer* first = &session.renderer(48, 32);
  session.render(cubeView(40, 30));
  EXPECT_EQ(session.pipelinesBuilt(), built);   // the pipelines serve every size
  EXPECT_EQ(&session.renderer(48, 32), first);  // two sizes kept
  EXPECT_EQ(session.compositor(40, 30).width(), 40);
  session.render(cubeView(24, 24));  // a third size: the least recently used goes
  EXPECT_EQ(session.pipelinesBuilt(), built);

  session.releaseRenderers();  // cold: the next frame compiles its pipelines again
  session.render(cubeView(48, 32));
  EXPECT_EQ(session.pipelinesBuilt(), 2 * built);
  EXPECT_EQ(session.context().validationErrors(), 0u);
}

TEST(RankSession, OtherListsOrTracersGetRenderersOfTheirOwn) {
  const Cube cube;
  RankSession session(vk::ContextOptions{}, nullptr, SessionOptions{{}, vk::Tracer::Auto, 4});
  cube.upload(session);
  comp::CompositorOptions fixed;
  fixed.mode = comp::ListMode::FixedMerge;
  render::Renderer& twoPass = session.renderer(32, 32);
  render::Renderer& merged = session.renderer(32, 32, fixed, vk::Tracer::Auto);
  EXPECT_NE(&twoPass, &merged);
  EXPECT_EQ(&session.renderer(32, 32, comp::CompositorOptions{}, vk::Tracer::Auto), &twoPass);
  const render::FrameResult a = twoPass.render(cubeView(32, 32));
  const render::FrameResult b = merged.render(cubeView(32, 32));
  EXPECT_GT(a.fragments, 0u);
  EXPECT_EQ(a.fragments, b.fragments);  // short lists: nothing merged away
  EXPECT_EQ(session.context().validationErrors(), 0u);
}

TEST(RankSession, ReplacingTheSceneKeepsItsCounts) {
  const Cube cube;
  prep::PreparedRank rank = cube.rank();
  RankSession session(vk::ContextOptions{}, nullptr);
  EXPECT_FALSE(session.hasScene());
  session.setScene(rank, rank.positions).setScalars(prep::gatherScalars(rank, cube.values));
  session.render(cubeView(16, 16));
  session.setScene(rank, rank.positions).setScalars(prep::gatherScalars(rank, cube.values));
  EXPECT_EQ(session.geometryBuilds(), 2u);
  EXPECT_EQ(session.scalarUploads(), 2u);
  session.releaseScene();
  EXPECT_FALSE(session.hasScene());
  EXPECT_EQ(session.geometryBuilds(), 2u);
  // Positions that are not the rank's are refused, naming both counts.
  EXPECT_THROW(session.setScene(rank, std::vector<float>(3)), Error);
}

}  // namespace
}  // namespace sm::session
