// Camera controller maths, without a window: orbit keeps the distance to the target, pan moves eye
// and target together, zoom changes the distance only (the parallel scale, in parallel
// projection), the projection toggle keeps the size at the target, and the pixel mappings make
// the object follow the cursor.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "common/error.h"
#include "viewer/camera_controller.h"

namespace sm::view {
namespace {

scene::Camera testCamera() {
  scene::Camera c;
  c.eye = {3.0, -4.0, 2.0};
  c.at = {0.5, 0.25, -0.5};
  c.up = {0, 0, 1};
  c.fovyDeg = 40.0;
  return c;
}

double dist(const scene::Camera& c) {
  return glm::length(c.eye - c.at);
}

glm::dvec3 direction(const scene::Camera& c) {
  return glm::normalize(c.at - c.eye);
}

// Pixel coordinates of a world point (inverse of scene::cameraFrame's pixel rays).
glm::dvec2 project(const scene::Camera& c, const glm::dvec3& p, int w, int h) {
  scene::CameraFrame f = scene::cameraFrame(c, w, h);
  const glm::dvec3 d = p - f.eye;
  const double z = glm::dot(d, f.forward);
  const double u = glm::dot(d, f.right) / z, v = glm::dot(d, f.upOrtho) / z;
  return {(u / (f.halfHeight * f.aspect) + 1) * w / 2 - 0.5, (1 - v / f.halfHeight) * h / 2 - 0.5};
}

TEST(CameraController, OrbitKeepsDistanceAndTarget) {
  CameraController cc(testCamera());
  const double d0 = cc.distance();
  const double turns[][2] = {{0.3, 0.1}, {-1.2, 0.4}, {2.5, -0.9}, {0.01, 0.02}, {-3.0, 0.7}};
  for (const auto& t : turns) {
    cc.orbit(t[0], t[1]);
    EXPECT_NEAR(dist(cc.camera()), d0, 1e-12 * d0);
    EXPECT_EQ(cc.camera().at, testCamera().at);
    EXPECT_EQ(cc.camera().up, testCamera().up);
  }
  EXPECT_GT(glm::length(cc.camera().eye - testCamera().eye), 0.1);  // it did move
}

TEST(CameraController, YawTurnsAboutUpAndComesBackAfterAFullTurn) {
  CameraController cc(testCamera());
  const double height0 = cc.camera().eye.z;
  for (int i = 0; i < 8; ++i) {
    cc.orbit(std::numbers::pi / 4, 0.0);
    EXPECT_NEAR(cc.camera().eye.z, height0, 1e-12);  // yaw alone keeps the elevation
  }
  EXPECT_NEAR(glm::length(cc.camera().eye - testCamera().eye), 0.0, 1e-12);
}

TEST(CameraController, ElevationStopsShortOfThePoles) {
  CameraController cc(testCamera());
  const double d0 = cc.distance();
  cc.orbit(0.0, 10.0);
  const glm::dvec3 offset = glm::normalize(cc.camera().eye - cc.camera().at);
  EXPECT_NEAR(std::asin(offset.z), CameraController::kMaxElevation, 1e-12);
  EXPECT_NEAR(cc.distance(), d0, 1e-12 * d0);
  EXPECT_NO_THROW(scene::cameraFrame(cc.camera(), 8, 8));  // never parallel to up
  cc.orbit(0.0, -20.0);
  EXPECT_NEAR(std::asin(glm::normalize(cc.camera().eye - cc.camera().at).z),
              -CameraController::kMaxElevation, 1e-12);
}

TEST(CameraController, DraggingRightMovesTheEyeLeftAndDraggingDownMovesItUp) {
  const scene::Camera c0 = testCamera();
  const scene::CameraFrame f0 = scene::cameraFrame(c0, 100, 100);
  CameraController right(c0), down(c0);
  right.orbitPixels(20, 0, 100);
  down.orbitPixels(0, 20, 100);
  EXPECT_LT(glm::dot(right.camera().eye - c0.eye, f0.right), 0.0);
  EXPECT_GT(glm::dot(down.camera().eye - c0.eye, f0.upOrtho), 0.0);
  // Half a turn per window height: 20 of 100 pixels is 36 degrees about up.
  const glm::dvec3 a = c0.eye - c0.at, b = right.camera().eye - c0.at;
  const double cosYaw = glm::dot(glm::normalize(glm::dvec2(a)), glm::normalize(glm::dvec2(b)));
  EXPECT_NEAR(std::acos(cosYaw), std::numbers::pi * 0.2, 1e-9);
}

TEST(CameraController, PanMovesEyeAndTargetTogether) {
  CameraController cc(testCamera());
  const scene::Camera c0 = cc.camera();
  cc.pan(0.7, -0.3);
  const scene::Camera& c1 = cc.camera();
  const glm::dvec3 moveEye = c1.eye - c0.eye, moveAt = c1.at - c0.at;
  EXPECT_NEAR(glm::length(moveEye - moveAt), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(moveEye), std::hypot(0.7, 0.3), 1e-12);
  EXPECT_NEAR(glm::dot(moveEye, direction(c0)), 0.0, 1e-12);  // in the image plane
  EXPECT_NEAR(dist(c1), dist(c0), 1e-12);
  EXPECT_NEAR(glm::length(direction(c1) - direction(c0)), 0.0, 1e-12);
}

TEST(CameraController, PanKeepsTheTargetUnderTheCursor) {
  const int w = 160, h = 120;
  CameraController cc(testCamera());
  const glm::dvec3 target = cc.camera().at;
  const glm::dvec2 before = project(cc.camera(), target, w, h);
  cc.panPixels(17, -9, h);
  const glm::dvec2 after = project(cc.camera(), target, w, h);
  EXPECT_NEAR(after.x - before.x, 17.0, 1e-9);
  EXPECT_NEAR(after.y - before.y, -9.0, 1e-9);
}

TEST(CameraController, ZoomChangesTheDistanceOnly) {
  CameraController cc(testCamera());
  const scene::Camera c0 = cc.camera();
  cc.zoom(0.5);
  EXPECT_NEAR(dist(cc.camera()), 0.5 * dist(c0), 1e-12);
  EXPECT_EQ(cc.camera().at, c0.at);
  EXPECT_NEAR(glm::length(direction(cc.camera()) - direction(c0)), 0.0, 1e-12);
  cc.zoomWheel(3);  // wheel away from the user: closer
  EXPECT_NEAR(dist(cc.camera()), 0.5 * std::pow(0.9, 3) * dist(c0), 1e-12);
  cc.zoomWheel(-3);
  cc.zoomPixels(-30, 120);  // drag up: closer
  EXPECT_LT(dist(cc.camera()), 0.5 * dist(c0));
  cc.zoom(0.0);  // ignored: the eye never lands on the target
  cc.zoom(-2.0);
  EXPECT_GT(dist(cc.camera()), 0.0);
  EXPECT_NEAR(glm::length(direction(cc.camera()) - direction(c0)), 0.0, 1e-12);
}

TEST(CameraController, ResetReturnsHome) {
  CameraController cc(testCamera());
  cc.orbit(1, 0.5);
  cc.pan(1, 1);
  cc.zoom(3);
  cc.reset();
  EXPECT_EQ(cc.camera().eye, testCamera().eye);
  EXPECT_EQ(cc.camera().at, testCamera().at);
}

TEST(CameraController, RejectsADegenerateHome) {
  scene::Camera c = testCamera();
  c.up = glm::normalize(c.at - c.eye);
  EXPECT_THROW(CameraController{c}, Error);
}

// `render --orbit`'s turn (scene::turnAbout) is the viewer's yaw: the same eye for the same angle,
// at, up, field of view, distance and height kept, a positive angle towards the camera's right,
// and a whole turn back where it started.
TEST(TurnAbout, IsTheViewersYawAndClosesAfterAWholeTurn) {
  const scene::Camera c = testCamera();
  for (double a : {0.3, -1.2, 2.5}) {
    CameraController cc(c);
    cc.orbit(a, 0.0);
    const scene::Camera t = scene::turnAbout(c, a);
    EXPECT_NEAR(glm::length(t.eye - cc.camera().eye), 0.0, 1e-12) << a;
    EXPECT_EQ(t.at, c.at);
    EXPECT_EQ(t.up, c.up);
    EXPECT_EQ(t.fovyDeg, c.fovyDeg);
    EXPECT_NEAR(dist(t), dist(c), 1e-12);
    EXPECT_NEAR(t.eye.z, c.eye.z, 1e-12);  // up is +z: the turn is horizontal
  }
  const glm::dvec3 right = scene::cameraFrame(c, 1, 1).right;
  EXPECT_GT(glm::dot(scene::turnAbout(c, 1e-3).eye - c.eye, right), 0.0);
  scene::Camera whole = c;
  for (int i = 0; i < 8; ++i) whole = scene::turnAbout(whole, std::numbers::pi / 4);
  EXPECT_NEAR(glm::length(whole.eye - c.eye), 0.0, 1e-12);
  // About a tilted up axis the eye stays on the circle about that axis through `at`.
  scene::Camera tilted = c;
  tilted.up = {0.0, 1.0, 1.0};
  const glm::dvec3 axis = glm::normalize(tilted.up);
  const scene::Camera tt = scene::turnAbout(tilted, 1.0);
  EXPECT_NEAR(glm::dot(tt.eye - c.at, axis), glm::dot(c.eye - c.at, axis), 1e-12);
  EXPECT_NEAR(dist(tt), dist(c), 1e-12);
}

// Pixel coordinates of a world point in a parallel view: its offset from the eye in the image
// plane, in units of the parallel scale.
glm::dvec2 projectParallel(const scene::Camera& c, const glm::dvec3& p, int w, int h) {
  scene::CameraFrame f = scene::cameraFrame(c, w, h);
  const glm::dvec3 d = p - f.eye;
  const double u = glm::dot(d, f.right), v = glm::dot(d, f.upOrtho);
  return {(u / (f.halfHeight * f.aspect) + 1) * w / 2 - 0.5, (1 - v / f.halfHeight) * h / 2 - 0.5};
}

scene::Camera parallelCamera() {
  scene::Camera c = testCamera();
  c.parallel = true;
  c.parallelScale = 1.5;
  return c;
}

TEST(CameraController, ParallelZoomChangesTheScaleNotTheEye) {
  CameraController cc(parallelCamera());
  cc.zoomWheel(2);  // in: the view holds less
  EXPECT_NEAR(cc.camera().parallelScale, 1.5 * 0.81, 1e-15);
  EXPECT_EQ(cc.camera().eye, parallelCamera().eye);
  cc.zoomPixels(50, 100);  // drag down: out
  EXPECT_NEAR(cc.camera().parallelScale, 1.5 * 0.81 * std::exp(1.0), 1e-12);
  EXPECT_EQ(cc.camera().eye, parallelCamera().eye);
  cc.zoom(0);  // ignored, as in perspective
  cc.zoom(-1);
  EXPECT_NEAR(cc.camera().parallelScale, 1.5 * 0.81 * std::exp(1.0), 1e-12);
}

// A pan by N pixels moves what is under the cursor by N pixels, in a parallel view at any depth.
TEST(CameraController, ParallelPanFollowsTheCursor) {
  const int w = 200, h = 100;
  CameraController cc(parallelCamera());
  const glm::dvec3 p = {0.9, 0.4, 0.1};
  const glm::dvec2 before = projectParallel(cc.camera(), p, w, h);
  cc.panPixels(12, -7, h);
  const glm::dvec2 after = projectParallel(cc.camera(), p, w, h);
  EXPECT_NEAR(after.x - before.x, 12, 1e-9);
  EXPECT_NEAR(after.y - before.y, -7, 1e-9);
}

// The point looked at keeps its size on screen: the parallel scale is the perspective view's
// half height at `at`, and back the eye moves to the distance where that holds; twice is the
// identity.
TEST(CameraController, ToggleProjectionKeepsTheSizeAtTheTarget) {
  const scene::Camera start = testCamera();
  CameraController cc(start);
  const double d = dist(start), tanHalf = std::tan(40.0 * std::numbers::pi / 360);
  cc.toggleProjection();
  EXPECT_TRUE(cc.camera().parallel);
  EXPECT_NEAR(cc.camera().parallelScale, d * tanHalf, 1e-12);
  EXPECT_EQ(cc.camera().eye, start.eye);
  cc.zoom(0.5);  // the parallel scale halves: back in perspective, half the distance
  cc.toggleProjection();
  EXPECT_FALSE(cc.camera().parallel);
  EXPECT_NEAR(dist(cc.camera()), 0.5 * d, 1e-12);
  EXPECT_NEAR(glm::length(direction(cc.camera()) - direction(start)), 0, 1e-12);
  cc.toggleProjection();
  cc.toggleProjection();
  EXPECT_NEAR(dist(cc.camera()), 0.5 * d, 1e-12);
}

}  // namespace
}  // namespace sm::view
