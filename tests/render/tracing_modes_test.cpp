// The two ways a two-pass frame traces its rays must give the same lists: the cached tracer (each
// ray traversed and marched once, the first segments cached between the passes, rays with more
// segments than cache slots traced again) and the stage-split tracer (traversal twice, then
// marching). And the traversal's stop at the rank's bounding box must only skip what is empty.
// Last, a frame's pixel storage handed back to the next render changes nothing in its image.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <limits>

#include "mesh/mesh_builder.h"
#include "prep/prepare.h"
#include "render_harness.h"
#include "test_meshes.h"
#include "vk/context.h"

namespace sm::render {
namespace {

using ref::test::Split;

// Slabs along z with gaps (one shell each, unwelded) behind a block: rays get 0 to 6 segments.
mesh::UnstructuredMesh layeredSlabs() {
  mesh::UnstructuredMesh m = ref::test::cubeMesh(Split::Tets5, 2, 1.0, {0, 0, 0});
  for (int k = 0; k < 5; ++k)
    mesh::append(m, ref::test::cubeMesh(k % 2 ? Split::Hex : Split::Tets6, 2, 0.6,
                                        {0.1 * k, 0.05 * k, 1.3 + 0.8 * k}));
  return m;
}

RenderSettings slabSettings(double earlyTermination) {
  RenderSettings s;
  s.width = s.height = 40;
  s.transferFunction = scene::makeTransferFunction("viridis");
  s.transferFunction.lo = -1;
  s.transferFunction.hi = 2;
  s.transferFunction.unitDistance = 0.4;
  s.dt = 0.017;
  s.integration = Integration::Sampled;  // the grid reference's samples
  s.earlyTermination = earlyTermination;
  s.keepSegments = true;  // these tests compare the segment lists too
  s.camera.eye = {0.45, 0.4, -2.5};
  s.camera.at = {0.55, 0.5, 3.0};
  s.camera.up = {0, 1, 0};
  s.camera.fovyDeg = 35;
  return s;
}

uint64_t cacheBytesForSlots(const RenderSettings& s, uint64_t slots) {
  return uint64_t(s.width) * s.height * slots * sizeof(gpu::CachedSegment);
}

bool sameBits(const void* a, const void* b, size_t n) {
  return std::memcmp(a, b, n) == 0;
}

void expectSameFrames(const std::string& name, const test::GpuRender& a, const test::GpuRender& b,
                      bool compareSegments) {
  ASSERT_EQ(a.fragments.size(), b.fragments.size()) << name;
  size_t differing = 0;
  for (size_t p = 0; p < a.fragments.size(); ++p) {
    const auto &fa = a.fragments[p], &fb = b.fragments[p];
    if (fa.size() != fb.size() || !sameBits(fa.data(), fb.data(), fa.size() * sizeof(fa[0])))
      ++differing;
    if (!compareSegments) continue;
    const auto &sa = a.segments[p], &sb = b.segments[p];
    if (sa.size() != sb.size() || !sameBits(sa.data(), sb.data(), sa.size() * sizeof(sa[0])))
      ++differing;
  }
  EXPECT_EQ(differing, 0u) << name << ": pixels whose lists differ";
  EXPECT_TRUE(sameBits(a.image.pixels.data(), b.image.pixels.data(),
                       a.image.pixels.size() * sizeof(a.image.pixels[0])))
      << name;
  EXPECT_EQ(a.validationErrors + b.validationErrors, 0u) << name;
  EXPECT_EQ(a.frame.counters.lostRays + b.frame.counters.lostRays, 0u) << name;
}

// Cache of 4 slots (default), 1 slot (most rays here are traced again in the store pass) and none
// (stage-split): bit-identical fragments, segments and images. Without early termination the
// segment lists are complete in every mode; with it, the fragments still agree.
TEST(TracingModes, CachedAndStageSplitListsAreIdentical) {
  auto m = layeredSlabs();
  auto f =
      ref::test::pointField(m, [](const glm::dvec3& p) { return p.x - 0.5 * p.y + 0.2 * p.z; });
  for (double et : {2.0, 0.99}) {
    RenderSettings s = slabSettings(et);
    if (et < 1.0) s.transferFunction.opacityScale = 40;  // most rays end inside the first slabs
    RenderSettings split = s, one = s;
    split.segmentCacheBytes = 0;
    one.segmentCacheBytes = cacheBytesForSlots(s, 1);
    auto cached = test::renderOnGpu(m, f, s), single = test::renderOnGpu(m, f, one),
         stageSplit = test::renderOnGpu(m, f, split);
    EXPECT_TRUE(cached.frame.timings.fused);
    EXPECT_FALSE(stageSplit.frame.timings.fused);
    size_t maxSegments = 0;
    for (const auto& p : stageSplit.segments) maxSegments = std::max(maxSegments, p.size());
    EXPECT_GE(maxSegments, et > 1.0 ? 5u : 1u);  // rays that overflow a one-slot cache exist
    if (et > 1.0) {
      // The count pass counts the pixels the store pass must trace again: those with more
      // segments than slots.
      uint32_t over1 = 0, over4 = 0;
      for (const auto& p : stageSplit.segments) {
        over1 += p.size() > 1 ? 1 : 0;
        over4 += p.size() > 4 ? 1 : 0;
      }
      EXPECT_GT(over4, 0u);
      EXPECT_EQ(single.frame.counters.cacheRetraces, over1);
      EXPECT_EQ(cached.frame.counters.cacheRetraces, over4);
    }
    std::string name = "early_termination_" + std::to_string(et);
    expectSameFrames(name + "_cache4", cached, stageSplit, et > 1.0);
    expectSameFrames(name + "_cache1", single, stageSplit, et > 1.0);
    // Without keepSegments (the default) the cached frame writes no segment list; its fragments
    // and image are the same.
    RenderSettings lean = s;
    lean.keepSegments = false;
    auto leanFrame = test::renderOnGpu(m, f, lean);
    expectSameFrames(name + "_lean", leanFrame, stageSplit, false);
    EXPECT_TRUE(leanFrame.segments.empty()) << name;
    test::expectImagesClose(name, test::renderReference(m, f, s), cached.image);
  }
}

// Where every pixel's segments fit in the cache, the store pass only copies (the tracer's store
// dispatch is skipped): the lists and image are still those of the stage-split tracer.
TEST(TracingModes, StorePassCopiesWhenTheCacheHoldsEveryRay) {
  auto cube = ref::test::cubeMesh(Split::Tets6, 3);
  auto f = ref::test::pointField(cube, [](const glm::dvec3& p) { return p.x + p.y * p.z; });
  RenderSettings s = slabSettings(2.0), split = s;
  s.camera.eye = {2.1, 1.7, -1.6};
  s.camera.at = {0.5, 0.5, 0.5};
  s.camera.up = {0, 0, 1};
  split = s;
  split.segmentCacheBytes = 0;
  auto cached = test::renderOnGpu(cube, f, s), stageSplit = test::renderOnGpu(cube, f, split);
  EXPECT_TRUE(cached.frame.timings.fused);
  EXPECT_GT(cached.frame.counters.segments, 0u);
  EXPECT_EQ(cached.frame.counters.cacheRetraces, 0u);
  expectSameFrames("cube_copy_only", cached, stageSplit, true);
}

// Rays leaving a box-shaped volume end their traversal there (no query for entries beyond), and
// rays missing the box make no query at all; rays leaving the front block between the slabs go on
// and find them, and the image matches the reference either way.
TEST(TracingModes, TraversalEndsAtTheBoundingBoxOnly) {
  // One cube: every ray that enters leaves through the bounding box.
  auto cube = ref::test::cubeMesh(Split::Tets6, 3);
  auto fc = ref::test::pointField(cube, [](const glm::dvec3& p) { return p.x + p.y * p.z; });
  RenderSettings s = slabSettings(2.0);
  s.camera.eye = {2.1, 1.7, -1.6};
  s.camera.at = {0.5, 0.5, 0.5};
  s.camera.up = {0, 0, 1};
  auto g = test::renderOnGpu(cube, fc, s);
  EXPECT_GT(g.frame.counters.segments, 0u);
  EXPECT_EQ(g.frame.counters.boxExits, g.frame.counters.segments);
  // One query per ray that enters (the probe at the box finds the entry), none for the others.
  EXPECT_LT(g.frame.counters.segments, uint32_t(s.width * s.height));
  EXPECT_EQ(g.frame.counters.shellQueries, g.frame.counters.segments);
  test::expectImagesClose("box_exit_cube", test::renderReference(cube, fc, s), g.image);
  // Block and slabs: a ray through the block exits through its back face, inside the box.
  auto m = layeredSlabs();
  auto f =
      ref::test::pointField(m, [](const glm::dvec3& p) { return p.x - 0.5 * p.y + 0.2 * p.z; });
  RenderSettings t = slabSettings(2.0);
  auto h = test::renderOnGpu(m, f, t);
  EXPECT_GT(h.frame.counters.boxExits, 0u);
  EXPECT_LT(h.frame.counters.boxExits, h.frame.counters.segments);
  EXPECT_GT(h.frame.counters.shellQueries, h.frame.counters.segments);  // "none beyond" costs one
  size_t pixelsWithSlabs = 0;
  for (const auto& p : h.segments) pixelsWithSlabs += p.size() >= 3 ? 1 : 0;
  EXPECT_GT(pixelsWithSlabs, 50u);
  test::expectImagesClose("box_exit_slabs", test::renderReference(m, f, t), h.image);
}

// The cached tracer first searches each entry close to where it is expected (the box entry, the
// end of the last segment; shell_query.glsl, nextCrossing), the stage-split tracer searches the
// whole ray: both must find the same crossings where that is hardest. Three unwelded blocks side
// by side along z (each entry lies exactly where the last segment ended, on faces shared by two
// shells: the tie between the exit and the entry triangle at the same t), a gap before the last,
// seen from outside, from inside the first block, and from inside the gap. From inside the first
// block, its exit and the second block's entry lie at the same distance: the eye is inside all the
// same (before the fix that came with this test, about half of those rays, by rounding, dropped
// the segment from the eye: RMSE 0.175 against the reference).
TEST(TracingModes, ProbedEntriesAreTheWholeRaysEntries) {
  mesh::UnstructuredMesh m = ref::test::cubeMesh(Split::Tets5, 3, 1.0, {0, 0, 0});
  mesh::append(m, ref::test::cubeMesh(Split::Hex, 2, 1.0, {0, 0, 1}));
  mesh::append(m, ref::test::cubeMesh(Split::Tets6, 2, 1.0, {0, 0, 2.5}));
  auto f = ref::test::pointField(m, [](const glm::dvec3& p) { return p.x + p.y - 0.3 * p.z; });
  struct View {
    const char* name;
    glm::dvec3 eye, at;
  };
  for (const View& v : {View{"outside", {0.3, 0.4, -2.0}, {0.5, 0.5, 2.0}},
                        View{"inside_block", {0.45, 0.55, 0.35}, {0.5, 0.5, 3.0}},
                        View{"inside_gap", {0.5, 0.45, 2.2}, {0.5, 0.5, -1.0}}}) {
    RenderSettings s = slabSettings(2.0);
    s.camera.eye = v.eye;
    s.camera.at = v.at;
    s.camera.fovyDeg = 60;
    RenderSettings split = s;
    split.segmentCacheBytes = 0;
    auto cached = test::renderOnGpu(m, f, s), stageSplit = test::renderOnGpu(m, f, split);
    ASSERT_TRUE(cached.frame.timings.fused) << v.name;
    size_t maxSegments = 0;
    for (const auto& p : stageSplit.segments) maxSegments = std::max(maxSegments, p.size());
    EXPECT_GE(maxSegments, std::string(v.name) == "inside_gap" ? 2u : 3u) << v.name;
    expectSameFrames(std::string("probe_") + v.name, cached, stageSplit, true);
    test::expectImagesClose(std::string("probe_") + v.name, test::renderReference(m, f, s),
                            cached.image);
  }
}

// The segment cache is an optimisation: where the device has no room for it (here: all but 400 KiB
// of a 64 MiB budget taken before the first frame, the cache wants 640 KiB) the frame runs
// stage-split and gives the same image; a budget below one slot per pixel does the same.
TEST(TracingModes, NoRoomForTheCacheFallsBackToStageSplit) {
  auto m = layeredSlabs();
  auto f =
      ref::test::pointField(m, [](const glm::dvec3& p) { return p.x - 0.5 * p.y + 0.2 * p.z; });
  RenderSettings s = slabSettings(2.0);
  s.width = s.height = 64;
  auto expected = test::renderOnGpu(m, f, s);
  ASSERT_TRUE(expected.frame.timings.fused);
  ::setenv("SHELLMARCH_DEVICE_MEMORY_LIMIT", "64M", 1);
  {
    test::RenderRig rig(m, f, s.width, s.height);
    vk::Context& ctx = rig.ctx;
    Renderer& renderer = rig.renderer;
    const uint64_t free = ctx.deviceMemoryLimit() - ctx.deviceMemoryInUse();
    ASSERT_GT(free, uint64_t(400) << 10);
    vk::Buffer hog(ctx, free - (uint64_t(400) << 10), vk::kStorageUsage, vk::MemoryUse::Device,
                   "test: memory taken");
    FrameResult r = renderer.render(s);
    EXPECT_FALSE(r.timings.fused);
    EXPECT_TRUE(sameBits(r.pixels.data(), expected.image.pixels.data(),
                         r.pixels.size() * sizeof(r.pixels[0])));
    EXPECT_FALSE(renderer.render(s).timings.fused);  // not tried again at the same size
    EXPECT_EQ(ctx.validationErrors(), 0u);
  }
  ::unsetenv("SHELLMARCH_DEVICE_MEMORY_LIMIT");
  RenderSettings tiny = s;
  tiny.segmentCacheBytes = uint64_t(s.width) * s.height * sizeof(gpu::CachedSegment) - 1;
  auto split = test::renderOnGpu(m, f, tiny);
  EXPECT_FALSE(split.frame.timings.fused);
  expectSameFrames("budget_below_one_slot", expected, split, true);
}

// A frame loop hands each frame's pixels back to the next render (Renderer::render's `reuse`):
// whatever that storage holds, and whatever its size, the image is the one a fresh frame gives,
// and storage of the image's size is taken over rather than allocated again (at 2048² a fresh
// 64 MiB image cost 35 ms of page faults per frame).
TEST(FrameStorage, AnEarlierFramesPixelsAreTakenOverWhateverTheyHold) {
  auto m = layeredSlabs();
  auto f = ref::test::pointField(m, [](const glm::dvec3& p) { return p.x + 0.3 * p.z; });
  RenderSettings s = slabSettings(2.0);
  s.width = 40;
  s.height = 24;
  const size_t n = size_t(s.width) * s.height;
  auto expected = test::renderOnGpu(m, f, s);
  test::RenderRig rig(m, f, s.width, s.height);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (size_t size : {n, 2 * n, size_t(10), size_t(0)}) {
    std::vector<glm::vec4> reuse(size, glm::vec4(nan));
    const glm::vec4* storage = reuse.data();
    FrameResult r = rig.renderer.render(s, std::move(reuse));
    ASSERT_EQ(r.pixels.size(), n) << "reused storage of " << size;
    EXPECT_TRUE(sameBits(r.pixels.data(), expected.image.pixels.data(), n * sizeof(glm::vec4)))
        << "reused storage of " << size;
    if (size >= n) {
      EXPECT_EQ(r.pixels.data(), storage) << "reused storage of " << size;
    }
  }
  EXPECT_EQ(rig.ctx.validationErrors(), 0u);
}

}  // namespace
}  // namespace sm::render
