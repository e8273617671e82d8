// Rendering with element filters and statistics: per-cluster fragments composite to the full
// image (invariant 4 for the oracle itself), counts of crossings and segments, non-finite
// scalars, early termination and input checking.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "common/error.h"
#include "ref/reference_renderer.h"
#include "test_meshes.h"

namespace sm::ref {
namespace {

using test::Split;

scene::TransferFunction testTf(double opacityScale) {
  auto tf = scene::makeTransferFunction("cool-to-warm");
  tf.lo = 0.0;
  tf.hi = 6.0;
  tf.opacityScale = opacityScale;
  return tf;
}

double linear(const glm::dvec3& p) {
  return p.x + 2 * p.y + 3 * p.z;
}

scene::Camera alongZ() {
  scene::Camera c;
  c.eye = {0.5, 0.5, -3.0};
  c.at = {0.5, 0.5, 0.5};
  c.up = {0, 1, 0};
  return c;
}

scene::Camera obliqueView() {
  scene::Camera c;
  c.eye = {1.9, -1.1, 1.7};
  c.at = {0.5, 0.5, 0.5};
  c.up = {0, 0, 1};
  return c;
}

TEST(RenderFilter, ClusterFragmentsCompositeToTheFullImage) {
  auto m = test::cubeMesh(Split::Tets6, 3, 1.0, glm::dvec3(0.0),
                          [](int i, int j, int k) { return (i + j + k) % 2; });
  ReferenceRenderer r(m);
  auto values = test::pointField(m, linear);
  const auto tf = testTf(5.0);
  const scene::Camera cam = obliqueView();
  const int size = 12;
  const auto frame = scene::cameraFrame(cam, size, size);
  for (RenderMode mode : {RenderMode::Grid, RenderMode::Converged}) {
    RenderSettings all{.dt = 0.013, .mode = mode};
    auto full = r.render(cam, size, size, values, tf, all);
    int multi = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        glm::dvec3 dir = frame.pixelDirection(x, y);
        std::vector<Fragment> frags;
        for (int32_t cluster : {0, 1}) {
          RenderSettings one = all;
          one.filter = clusterPredicate(m, {cluster});
          auto f = r.fragments(frame.eye, dir, values, tf, one);
          frags.insert(frags.end(), f.begin(), f.end());
        }
        multi += frags.size() > 2;
        std::sort(frags.begin(), frags.end(), [](auto& a, auto& b) { return a.depth < b.depth; });
        glm::dvec3 c(0.0);
        double a = 0.0;
        for (const auto& f : frags) {
          c += (1.0 - a) * f.color;
          a += (1.0 - a) * f.alpha;
        }
        auto whole = r.fragments(frame.eye, dir, values, tf, all);
        ASSERT_EQ(whole.size(), frags.empty() ? 0u : 1u);
        // Grid: the same samples, so equal up to rounding. Converged: each within tolerance.
        const double tol = mode == RenderMode::Grid ? 1e-12 : 2e-6;
        if (!whole.empty()) {
          EXPECT_NEAR(whole[0].alpha, a, tol);
          EXPECT_NEAR(whole[0].color.r, c.r, tol);
        }
        EXPECT_NEAR(full.image.at(x, y).a, a, std::max(tol, 1e-6));
        EXPECT_NEAR(full.image.at(x, y).b, c.b, std::max(tol, 1e-6));
      }
    EXPECT_GT(multi, size * size / 4);  // the clusters interleave along most rays
  }
}

TEST(RenderFilter, StatisticsCountCrossingsAndSegments) {
  auto m =
      test::cubeMesh(Split::Hex, 3, 1.0, glm::dvec3(0.0), [](int, int, int k) { return k % 2; });
  ReferenceRenderer r(m);
  auto values = test::pointField(m, linear);
  const int size = 33;  // odd: the centre pixel looks exactly along the axis
  auto full = r.render(alongZ(), size, size, values, testTf(1.0), {.dt = 0.05});
  const PixelStats& centre = full.stats[16 * size + 16];
  EXPECT_EQ(centre.crossings, 3u);
  EXPECT_EQ(centre.segments, 1u);
  EXPECT_EQ(centre.samples, 20u);  // t in [3, 4): k = 60 .. 79
  EXPECT_EQ(full.stats[0].crossings, 0u);
  EXPECT_EQ(full.image.at(0, 0), glm::vec4(0.0f));
  RenderSettings even{.dt = 0.05, .filter = clusterPredicate(m, {0})};
  auto part = r.render(alongZ(), size, size, values, testTf(1.0), even);
  EXPECT_EQ(part.stats[16 * size + 16].crossings, 2u);
  EXPECT_EQ(part.stats[16 * size + 16].segments, 2u);
}

// Elements with a NaN vertex value render as empty space: the same image as leaving them out.
TEST(RenderFilter, NonFiniteScalarsAreTransparent) {
  auto m =
      test::cubeMesh(Split::Wedges, 2, 1.0, glm::dvec3(0.0), [](int i, int, int) { return i; });
  ReferenceRenderer r(m);
  auto finite = test::pointField(m, linear);
  auto poisoned =
      test::pointField(m, [](const glm::dvec3& p) { return p.x > 0.75 ? NAN : linear(p); });
  for (RenderMode mode : {RenderMode::Grid, RenderMode::Converged}) {
    RenderSettings left{.dt = 0.02, .mode = mode, .filter = clusterPredicate(m, {0})};
    auto want = r.render(obliqueView(), 16, 16, finite, testTf(3.0), left).image;
    auto got = r.render(obliqueView(), 16, 16, poisoned, testTf(3.0), {.dt = 0.02, .mode = mode});
    // Converged mode spreads its tolerance over different lengths: equal to within it.
    EXPECT_LT(scene::compareImages(want, got.image).maxAbs, 2e-6);
    EXPECT_EQ(scene::compareImages(want, got.image).nanPixels, 0);
  }
}

TEST(RenderFilter, EarlyTerminationStopsAtTheThreshold) {
  auto m = test::cubeMesh(Split::Tets5, 2);
  ReferenceRenderer r(m);
  auto values = test::pointField(m, linear);
  auto tf = testTf(40.0);
  auto full = r.render(alongZ(), 9, 9, values, tf, {.dt = 0.01});
  auto early = r.render(alongZ(), 9, 9, values, tf, {.dt = 0.01, .earlyTermination = 0.99});
  int opaque = 0;
  for (size_t i = 0; i < full.stats.size(); ++i) {
    if (!(full.image.pixels[i].a > 0.999f)) continue;  // short paths near the silhouette
    ++opaque;
    EXPECT_GE(early.image.pixels[i].a, 0.99f);
    EXPECT_LT(early.image.pixels[i].a, full.image.pixels[i].a);
    EXPECT_LT(early.stats[i].samples, full.stats[i].samples);
  }
  EXPECT_GT(opaque, 20);
}

TEST(RenderFilter, InvalidInputsThrow) {
  auto m = test::cubeMesh(Split::Hex, 1);
  ReferenceRenderer r(m);
  auto values = test::pointField(m, linear);
  auto tf = testTf(1.0);
  std::vector<float> tooFew(values.begin(), values.end() - 1);
  EXPECT_THROW(r.render(alongZ(), 4, 4, tooFew, tf, {.dt = 0.1}), Error);
  EXPECT_THROW(r.render(alongZ(), 4, 4, values, tf, {.dt = 0.0}), Error);
  EXPECT_THROW(r.render(alongZ(), 4, 4, values, tf, {.dt = 0.1, .earlyTermination = 0.0}), Error);
  EXPECT_THROW(r.render(alongZ(), 0, 4, values, tf, {.dt = 0.1}), Error);
  EXPECT_NO_THROW(r.render(alongZ(), 4, 4, values, tf, {.mode = RenderMode::Converged}));
}

}  // namespace
}  // namespace sm::ref
