// The camera's pixel rays (scene/camera.h), perspective and parallel, framing and the default up.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "common/error.h"
#include "scene/camera.h"

namespace sm::scene {
namespace {

Camera obliqueParallel(double scale) {
  Camera c;
  c.eye = {3, -2, 1.5};
  c.at = {0.5, 0.25, 0};
  c.up = {0, 0, 1};
  c.parallel = true;
  c.parallelScale = scale;
  return c;
}

mesh::Bounds box(glm::dvec3 lo, glm::dvec3 hi) {
  mesh::Bounds b;
  b.extend(lo);
  b.extend(hi);
  return b;
}

TEST(ParallelCamera, EveryRayRunsAlongTheViewingDirection) {
  const Camera c = obliqueParallel(0.7);
  const CameraFrame f = cameraFrame(c, 9, 5);
  const glm::dvec3 forward = glm::normalize(c.at - c.eye);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 9; ++x) {
      const glm::dvec3 d = f.pixelDirection(x, y);
      EXPECT_NEAR(glm::length(d - forward), 0.0, 1e-15) << x << "," << y;
    }
}

// The image's edges lie parallelScale above and below the eye and parallelScale * W / H to the
// sides, on the plane through the eye facing the camera; pixel centres are half a pixel inside.
TEST(ParallelCamera, OriginsSpanTheParallelScaleOnThePlaneThroughTheEye) {
  const double scale = 0.7;
  const int w = 8, h = 4;
  const Camera c = obliqueParallel(scale);
  const CameraFrame f = cameraFrame(c, w, h);
  const glm::dvec3 forward = glm::normalize(c.at - c.eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, c.up));
  const glm::dvec3 up = glm::cross(right, forward);
  auto local = [&](glm::dvec3 p) {
    p -= c.eye;
    return glm::dvec3(glm::dot(p, right), glm::dot(p, up), glm::dot(p, forward));
  };
  // Image corners (pixel coordinates 0 and W, H).
  EXPECT_NEAR(glm::length(local(f.origin(0, 0)) - glm::dvec3(-scale * w / h, scale, 0)), 0, 1e-14);
  EXPECT_NEAR(glm::length(local(f.origin(w, h)) - glm::dvec3(scale * w / h, -scale, 0)), 0, 1e-14);
  // Neighbouring pixel centres are one pixel apart: 2 scale / H in both directions.
  const double pixel = 2 * scale / h;
  EXPECT_NEAR(glm::length(f.pixelOrigin(3, 1) - f.pixelOrigin(2, 1)), pixel, 1e-14);
  EXPECT_NEAR(glm::length(f.pixelOrigin(3, 2) - f.pixelOrigin(3, 1)), pixel, 1e-14);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) EXPECT_NEAR(local(f.pixelOrigin(x, y)).z, 0.0, 1e-14);
}

// Pixel (x, y) and its mirror (W-1-x, H-1-y) lie symmetrically about the eye: the image is
// centred on the line of sight, in both projections.
TEST(ParallelCamera, PixelCentresAreSymmetricAboutTheLineOfSight) {
  for (bool parallel : {true, false}) {
    Camera c = obliqueParallel(1.3);
    c.parallel = parallel;
    const int w = 7, h = 6;
    const CameraFrame f = cameraFrame(c, w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const glm::dvec3 o = f.pixelOrigin(x, y) + f.pixelOrigin(w - 1 - x, h - 1 - y);
        EXPECT_NEAR(glm::length(o * 0.5 - c.eye), 0.0, 1e-14);
        const glm::dvec3 d = f.pixelDirection(x, y) + f.pixelDirection(w - 1 - x, h - 1 - y);
        EXPECT_NEAR(glm::length(glm::cross(d, f.forward)), 0.0, 1e-14);
      }
    // An odd width puts the middle column on the line of sight.
    EXPECT_NEAR(glm::dot(f.pixelOrigin(3, 0) - c.eye, f.right), 0.0, 1e-14);
  }
}

TEST(ParallelCamera, PerspectiveRaysStillStartAtTheEye) {
  Camera c = obliqueParallel(1.0);
  c.parallel = false;
  c.fovyDeg = 40;
  const CameraFrame f = cameraFrame(c, 10, 10);
  EXPECT_EQ(f.pixelOrigin(0, 9), c.eye);
  // The top edge's ray makes half the field of view with the line of sight.
  const double angle = std::acos(glm::dot(f.direction(5, 0), f.forward));
  EXPECT_NEAR(glm::degrees(angle), 20.0, 1e-12);
}

TEST(ParallelCamera, ABadScaleIsRefusedNamingTheOption) {
  for (double bad : {0.0, -1.0, std::nan(""), 1e31}) {
    try {
      cameraFrame(obliqueParallel(bad), 4, 4);
      ADD_FAILURE() << "scale " << bad << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("--parallel-scale"), std::string::npos) << e.what();
    }
  }
}

// The bounding sphere fits both directions: the scale is the radius (with the 2% margin) over
// the smaller of 1 and the aspect ratio, and the eye sits where the perspective one does.
TEST(FrameBounds, ParallelFramingFitsTheBoundingSphere) {
  const mesh::Bounds b = box({-1, 0, 2}, {3, 2, 6});  // radius 3
  for (double aspect : {0.5, 1.0, 2.0}) {
    const Camera p = frameBounds(b, ViewPreset::Iso, aspect, 30, Projection::Parallel);
    const Camera q = frameBounds(b, ViewPreset::Iso, aspect, 30);
    EXPECT_TRUE(p.parallel);
    EXPECT_FALSE(q.parallel);
    EXPECT_EQ(p.eye, q.eye);
    EXPECT_EQ(p.at, q.at);
    const double halfHeight = p.parallelScale, halfWidth = p.parallelScale * aspect;
    EXPECT_NEAR(std::min(halfHeight, halfWidth), 3 * 1.02, 1e-12) << aspect;
    EXPECT_DOUBLE_EQ(fitParallelScale(b, aspect), p.parallelScale);
    // The eye is in front of all the data: no ray starts inside.
    EXPECT_GT(glm::length(p.eye - b.center()), 3.0);
  }
}

// +z is up, except when looking along z, where +z would be the viewing direction.
TEST(DefaultUp, IsZUpExceptAlongZ) {
  EXPECT_EQ(defaultUp({1, 0, 0}), glm::dvec3(0, 0, 1));
  EXPECT_EQ(defaultUp({-1, -1.3, -0.8}), glm::dvec3(0, 0, 1));
  EXPECT_EQ(defaultUp({0, 0, 1}), glm::dvec3(0, 1, 0));
  EXPECT_EQ(defaultUp({0, 0, -5}), glm::dvec3(0, 1, 0));
  EXPECT_EQ(defaultUp({0.001, 0, -1}), glm::dvec3(0, 1, 0));  // within a degree of z
  EXPECT_EQ(defaultUp({0.1, 0, -1}), glm::dvec3(0, 0, 1));    // about 6 degrees off
  const mesh::Bounds b = box({0, 0, 0}, {1, 1, 1});
  for (ViewPreset v :
       {ViewPreset::Iso, ViewPreset::PosX, ViewPreset::NegX, ViewPreset::PosY, ViewPreset::NegY})
    EXPECT_EQ(frameBounds(b, v, 1.0).up, glm::dvec3(0, 0, 1));
  for (ViewPreset v : {ViewPreset::PosZ, ViewPreset::NegZ})
    EXPECT_EQ(frameBounds(b, v, 1.0).up, glm::dvec3(0, 1, 0));
}

TEST(TurnAbout, KeepsTheProjection) {
  const Camera c = obliqueParallel(0.9);
  const Camera t = turnAbout(c, 0.7);
  EXPECT_TRUE(t.parallel);
  EXPECT_EQ(t.parallelScale, 0.9);
}

}  // namespace
}  // namespace sm::scene
