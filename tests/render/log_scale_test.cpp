// A log scale (--log-scale): the homogeneous slab's known answer at the log coordinate of its
// scalar, values <= 0 at the table's first entry, images against the CPU reference for every
// element type on a field that spans three decades, element-exact integration against the
// continuous integral, and the ranges it refuses.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "common/error.h"
#include "ref/reference_renderer.h"
#include "render_harness.h"
#include "scene/camera.h"
#include "test_meshes.h"

namespace sm::render {
namespace {

using ref::test::Split;

RenderSettings slabSettings() {
  RenderSettings s;
  s.width = s.height = 40;
  s.camera.eye = {1.9, 2.3, 2.7};
  s.camera.at = {0.5, 0.5, 0.5};
  s.camera.up = {0, 0, 1};
  s.camera.fovyDeg = 40;
  s.dt = 0.01;
  // The sampled scheme (the element-exact tests ask for theirs).
  s.integration = Integration::Sampled;
  s.earlyTermination = 2.0;  // off: compare the whole integral
  return s;
}

// Per pixel, the sampled scheme's 1 - exp(-sigma dt)^n for the n grid samples in the cube, but for
// a ray whose entry or exit lies within rounding of a sample (one sample more or less there).
void expectSlab(const test::GpuRender& r, const RenderSettings& s, double sigma, const char* what) {
  EXPECT_EQ(r.validationErrors, 0u);
  EXPECT_EQ(r.frame.counters.lostRays, 0u);
  const auto cam = scene::cameraFrame(s.camera, s.width, s.height);
  const double tol = 1e-4;
  auto scheme = [&](double n) { return 1.0 - std::pow(std::exp(-sigma * s.dt), n); };
  int hit = 0, moved = 0;
  double worst = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      double t0, t1;
      test::rayBox(cam.eye, cam.pixelDirection(x, y), glm::dvec3(0.0), glm::dvec3(1.0), t0, t1);
      const double n = t1 > t0 ? std::ceil(t1 / s.dt) - std::ceil(t0 / s.dt) : 0.0;
      const double alpha = r.image.at(x, y).a, err = std::abs(alpha - scheme(n));
      hit += n > 0;
      if (err > tol && n > 0 &&
          std::min(std::abs(alpha - scheme(n - 1)), std::abs(alpha - scheme(n + 1))) <= tol) {
        ++moved;
        continue;
      }
      worst = std::max(worst, err);
    }
  std::printf("[log scale] %s: max |alpha - expected| = %.2g over %d pixels (%d samples moved)\n",
              what, worst, hit, moved);
  EXPECT_GT(hit, s.width * s.height / 4) << what;
  EXPECT_LT(worst, tol) << what;
  EXPECT_LE(moved, 3) << what;
}

// The grayscale map (opacity ramping from 0 to 1) on a log scale over [1, 1000], where 10 sits a
// third of the way up.
scene::TransferFunction thirdOfTheWay() {
  scene::TransferFunction tf = scene::makeTransferFunction("grayscale");
  tf.lo = 1.0;
  tf.hi = 1000.0;
  tf.scale = scene::ScalarScale::Log;
  tf.unitDistance = 0.4;
  return tf;
}

// Scalar 10 over [1, 1000] sits a third of the way up a log scale (a linear one would put it at
// 0.009): the grayscale map's opacity ramp gives it opacity 1/3.
TEST(LogScale, SlabOpacityIsTakenAtTheLogCoordinate) {
  auto m = ref::test::cubeMesh(Split::Tets5, 3);
  RenderSettings s = slabSettings();
  s.transferFunction = thirdOfTheWay();
  const double sigma = (1.0 / 3.0) / 0.4;
  auto r =
      test::renderOnGpu(m, ref::test::pointField(m, [](const glm::dvec3&) { return 10.0; }), s);
  expectSlab(r, s, sigma, "scalar 10 on [1, 1000]");
}

// Zero and negative values have no logarithm: they fall below the range, onto the first entry,
// as values under lo do (not NaN, which would render transparent).
TEST(LogScale, ValuesAtOrBelowZeroTakeTheFirstEntry) {
  auto m = ref::test::cubeMesh(Split::Hex, 3);
  RenderSettings s = slabSettings();
  s.transferFunction = scene::makeTransferFunction("grayscale");
  for (glm::vec4& e : s.transferFunction.table) e.a = 0.0f;
  s.transferFunction.table.front().a = 1.0f;  // only the first entry is opaque
  s.transferFunction.lo = 0.5;
  s.transferFunction.hi = 50.0;
  s.transferFunction.scale = scene::ScalarScale::Log;
  s.transferFunction.unitDistance = 1.0 / 1.3;
  for (double v : {0.0, -2.0, 0.25}) {
    auto r =
        test::renderOnGpu(m, ref::test::pointField(m, [v](const glm::dvec3&) { return v; }), s);
    expectSlab(r, s, 1.3, v == 0.0 ? "scalar 0" : v < 0.0 ? "scalar -2" : "scalar 0.25 (below lo)");
  }
}

// 10^(x + y + z): three decades over the cube, so that a linear scale would leave most of it in
// the map's first few entries. Grid-mode reference, default tolerance (RMSE 1/255).
TEST(LogScale, ImagesMatchTheReference) {
  for (Split split : ref::test::kAllSplits) {
    auto m = ref::test::cubeMesh(split, 3);
    auto f = ref::test::pointField(
        m, [](const glm::dvec3& p) { return std::pow(10.0, p.x + p.y + p.z); });
    RenderSettings s = slabSettings();
    s.width = s.height = 56;
    s.dt = 0.0137;
    s.transferFunction = scene::makeTransferFunction("viridis");
    s.transferFunction.lo = 1.0;
    s.transferFunction.hi = 1000.0;
    s.transferFunction.scale = scene::ScalarScale::Log;
    s.transferFunction.unitDistance = 0.3;
    auto gpu = test::renderOnGpu(m, f, s);
    EXPECT_EQ(gpu.validationErrors, 0u);
    EXPECT_EQ(gpu.frame.counters.lostRays, 0u);
    const scene::Image want = test::renderReference(m, f, s);
    const scene::ImageError err =
        test::expectImagesClose("log_scale_" + ref::test::splitName(split), want, gpu.image);
    // The same frame on a linear scale is a different image: the scale reached the device.
    s.transferFunction.scale = scene::ScalarScale::Linear;
    const scene::ImageError linear = scene::compareImages(want, test::renderOnGpu(m, f, s).image);
    EXPECT_GT(linear.rmse, 20 * err.rmse + 1e-3) << ref::test::splitName(split);
    std::printf("[log scale] %s: RMSE %.2g against the reference (%.2g on a linear scale)\n",
                ref::test::splitName(split).c_str(), err.rmse, linear.rmse);
  }
}

// Element-exact on a log scale: the slab's continuous answer 1 - exp(-sigma L) (to the table's
// 1e-3), and images against the reference's continuous integral of the three-decade field.
TEST(LogScale, ElementExactGivesTheContinuousIntegral) {
  auto m = ref::test::cubeMesh(Split::Tets5, 3);
  RenderSettings s = slabSettings();
  s.integration = Integration::ElementExact;
  s.transferFunction = thirdOfTheWay();
  const double sigma = (1.0 / 3.0) / 0.4;
  auto slab =
      test::renderOnGpu(m, ref::test::pointField(m, [](const glm::dvec3&) { return 10.0; }), s);
  EXPECT_EQ(slab.validationErrors, 0u);
  const auto cam = scene::cameraFrame(s.camera, s.width, s.height);
  double worst = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      double t0, t1;
      test::rayBox(cam.eye, cam.pixelDirection(x, y), glm::dvec3(0.0), glm::dvec3(1.0), t0, t1);
      const double L = t1 > t0 ? t1 - t0 : 0.0;
      worst = std::max(worst, std::abs(slab.image.at(x, y).a - (1.0 - std::exp(-sigma * L))));
    }
  std::printf("[log scale] exact slab: max |alpha - expected| = %.2g\n", worst);
  EXPECT_LT(worst, 1e-3);

  for (Split split : {Split::Tets6, Split::Wedges, Split::Hex}) {
    auto mesh = ref::test::cubeMesh(split, 3);
    auto decades = [](const glm::dvec3& p) { return std::pow(10.0, p.x + p.y + p.z); };
    RenderSettings e = slabSettings();
    e.width = e.height = 48;
    e.dt = 0.0137;
    e.integration = Integration::ElementExact;
    e.transferFunction = scene::makeTransferFunction("viridis");
    e.transferFunction.lo = 1.0;
    e.transferFunction.hi = 1000.0;
    e.transferFunction.scale = scene::ScalarScale::Log;
    e.transferFunction.unitDistance = 0.3;
    auto gpu = test::renderOnGpu(mesh, ref::test::pointField(mesh, decades), e);
    EXPECT_EQ(gpu.frame.counters.lostRays, 0u);
    mesh::UnstructuredMesh ordered = test::inGlobalVertexOrder(mesh);
    ref::ReferenceRenderer reference(ordered);
    ref::RenderSettings rs;
    rs.mode = ref::RenderMode::Converged;
    auto want = reference.render(e.camera, e.width, e.height,
                                 ref::test::pointField(ordered, decades), e.transferFunction, rs);
    test::ImageCheck check;
    check.maxRmse = 1e-4;  // measured 1.4e-5 to 1.7e-5: the colour table's interpolation
    check.maxAbs = 1e-3;
    const scene::ImageError err = test::expectImagesClose(
        "log_exact_" + ref::test::splitName(split), want.image, gpu.image, check);
    std::printf("[log scale] exact %s: RMSE %.2g, max abs %.2g against the continuous integral\n",
                ref::test::splitName(split).c_str(), err.rmse, err.maxAbs);
  }
}

TEST(LogScale, RefusesANonPositiveRange) {
  auto m = ref::test::cubeMesh(Split::Tets5, 2);
  auto f = ref::test::pointField(m, [](const glm::dvec3& p) { return 1.0 + p.x; });
  RenderSettings s = slabSettings();
  s.transferFunction = scene::makeTransferFunction("viridis");
  s.transferFunction.scale = scene::ScalarScale::Log;
  s.transferFunction.hi = 2.0;
  for (double lo : {0.0, -1.0}) {
    s.transferFunction.lo = lo;
    for (Integration integration : {Integration::Sampled, Integration::ElementExact}) {
      s.integration = integration;
      try {
        test::renderOnGpu(m, f, s);
        ADD_FAILURE() << "range " << lo << " .. 2 accepted";
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("--log-scale: a log scale needs a positive range"),
                  std::string::npos)
            << e.what();
      }
    }
  }
}

}  // namespace
}  // namespace sm::render
