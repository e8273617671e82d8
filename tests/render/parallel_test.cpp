// Parallel projection (scene::Camera::parallel): the slab's known answer for the length each
// ray crosses, images against the CPU reference (which both tracers must give bit for bit: the
// harness renders each case's first frame with both), and rays that start inside the volume
// where the image plane cuts through it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "ref/reference_renderer.h"
#include "render_harness.h"
#include "scene/camera.h"
#include "test_meshes.h"

namespace sm::render {
namespace {

using ref::test::Split;

RenderSettings parallelView(int w, int h) {
  RenderSettings s = test::cubeView(w, h);
  s.camera.parallel = true;
  s.camera.parallelScale = 0.95;
  return s;
}

// Constant extinction: each pixel's opacity is 1 - exp(-sigma L), L the length of its ray (from
// its own origin on the image plane, along the viewing direction) inside the cube. Element-exact
// integration reaches it to the pre-integration table's 1e-3.
TEST(ParallelProjection, SlabOpacityFollowsEachRaysLength) {
  const double sigma = 1.7;
  RenderSettings s = parallelView(40, 30);
  s.transferFunction = test::constantTransferFunction({0.9f, 0.5f, 0.1f}, 1.0f, 1.0 / sigma);
  s.earlyTermination = 2.0;
  auto r = test::renderOnGpu(ref::test::cubeMesh(Split::Tets5, 3), "", s);
  EXPECT_EQ(r.validationErrors, 0u);
  EXPECT_EQ(r.frame.counters.lostRays, 0u);
  const scene::CameraFrame cam = scene::cameraFrame(s.camera, s.width, s.height);
  int hit = 0, missed = 0;
  double worst = 0, longest = 0, shortest = 10;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      double t0, t1;
      test::rayBox(cam.pixelOrigin(x, y), cam.pixelDirection(x, y), glm::dvec3(0.0),
                   glm::dvec3(1.0), t0, t1);
      const double length = t1 > t0 ? t1 - t0 : 0.0;
      const double expected = 1.0 - std::exp(-sigma * length);
      worst = std::max(worst, std::abs(double(r.image.at(x, y).a) - expected));
      if (length > 0) {
        ++hit;
        longest = std::max(longest, length);
        shortest = std::min(shortest, length);
      } else {
        ++missed;
      }
    }
  std::printf("[parallel] slab: max |alpha - expected| = %.2g over %d rays in, %d past the cube\n",
              worst, hit, missed);
  // The view holds the whole cube with background around it, and the lengths vary (a
  // perspective image of the same lengths would not match).
  EXPECT_GT(hit, s.width * s.height / 4);
  EXPECT_GT(missed, s.width * s.height / 10);
  EXPECT_GT(longest - shortest, 0.5);
  EXPECT_LT(worst, 1e-3);
}

double wavy(const glm::dvec3& p) {
  return std::sin(3.0 * p.x) + p.y * p.y + 0.5 * p.z;
}

// Every element type, sampled on the grid the reference samples, at RMSE 1/255.
TEST(ParallelProjection, SampledImagesMatchTheReference) {
  for (Split split : ref::test::kAllSplits) {
    auto m = ref::test::cubeMesh(split, 3);
    auto f = ref::test::pointField(m, wavy);
    RenderSettings s = parallelView(48, 40);
    s.transferFunction.lo = -0.2;
    s.transferFunction.hi = 2.0;
    s.integration = Integration::Sampled;
    s.earlyTermination = 2.0;
    auto gpu = test::renderOnGpu(m, f, s);
    EXPECT_EQ(gpu.validationErrors, 0u);
    EXPECT_EQ(gpu.frame.counters.lostRays, 0u);
    EXPECT_EQ(gpu.frame.counters.cameraInside, 0u);
    test::expectImagesClose("parallel_" + ref::test::splitName(split),
                            test::renderReference(m, f, s), gpu.image);
  }
}

// The image plane through the eye cuts the cube: rays that start inside begin their first
// segment at their origin (the part behind the plane is not seen), as the reference's do.
TEST(ParallelProjection, RaysStartingInsideTheVolumeMatchTheReference) {
  auto m = ref::test::cubeMesh(Split::Hex, 3);
  auto f = ref::test::pointField(m, wavy);
  RenderSettings s = parallelView(48, 48);
  s.camera.eye = {0.6, 0.45, 0.55};
  s.camera.at = {1.6, 1.2, 0.9};
  s.camera.parallelScale = 0.6;
  s.transferFunction.lo = -0.2;
  s.transferFunction.hi = 2.0;
  s.integration = Integration::Sampled;
  s.earlyTermination = 2.0;
  auto gpu = test::renderOnGpu(m, f, s);
  EXPECT_EQ(gpu.validationErrors, 0u);
  EXPECT_EQ(gpu.frame.counters.lostRays, 0u);
  EXPECT_GT(gpu.frame.counters.cameraInside, uint32_t(s.width * s.height / 4));
  test::expectImagesClose("parallel_inside", test::renderReference(m, f, s), gpu.image);
}

// Same rays, same image: a parallel camera far away and one just outside the data, the same
// direction and scale, give the same pixels up to float rounding of the origins (t differs by a
// constant, and element-exact integration has no grid to shift).
TEST(ParallelProjection, TheEyesDistanceDoesNotChangeTheImage) {
  auto m = ref::test::cubeMesh(Split::Wedges, 3);
  auto f = ref::test::pointField(m, wavy);
  RenderSettings near = parallelView(32, 32);
  near.transferFunction.lo = -0.2;
  near.transferFunction.hi = 2.0;
  RenderSettings far = near;
  far.camera.eye = far.camera.at + 4.0 * (near.camera.eye - near.camera.at);
  auto a = test::renderOnGpu(m, f, near);
  auto b = test::renderOnGpu(m, f, far);
  const scene::ImageError e = scene::compareImages(a.image, b.image);
  EXPECT_LT(e.maxAbs, 2e-3) << "RMSE " << e.rmse;
  EXPECT_EQ(b.frame.counters.lostRays, 0u);
}

}  // namespace
}  // namespace sm::render
