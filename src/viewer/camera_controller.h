// Turntable camera control for the viewer: orbit about the point looked at, pan, zoom, and the
// switch between perspective and parallel projection. The up
// vector stays the user's (the world's) up, as in ParaView's default interaction, and the
// elevation stops short of it, so the view never flips or rolls.
//
// Screen conventions (window pixels, y down): the object follows the cursor. Dragging right turns
// the object right (the eye moves left around it); dragging down turns its front down (the eye
// moves up); a pan keeps the point under the cursor at the depth of `at` under the cursor.
#pragma once

#include "scene/camera.h"

namespace sm::view {

class CameraController {
 public:
  explicit CameraController(const scene::Camera& home);

  const scene::Camera& camera() const { return cam_; }
  void setCamera(const scene::Camera& c) { cam_ = c; }
  void reset() { cam_ = home_; }
  double distance() const;

  // Rotates the eye about `at`: yaw about up (positive moves the eye towards the camera's right),
  // then elevation (positive moves the eye up), clamped to within kMaxElevation of the poles.
  // The distance to `at` is unchanged.
  void orbit(double yawRad, double elevationRad);
  // Moves eye and at together by `right` and `up` world units along the camera's right and
  // (orthogonalised) up directions.
  void pan(double right, double up);
  // Multiplies the distance from at to the eye by `factor` (> 0); the direction is unchanged.
  // With a parallel projection, where distance changes nothing on screen, multiplies the parallel
  // scale instead (as ParaView's zoom does).
  void zoom(double factor);
  // Perspective <-> parallel, keeping the size on screen of what lies at `at`: the parallel scale
  // becomes the perspective half height there, distance * tan(fovy / 2); back, the eye moves
  // along the viewing direction to the distance at which that holds again.
  void toggleProjection();

  // The same in window pixels for a viewport `height` pixels high.
  void orbitPixels(double dx, double dy, int height);
  void panPixels(double dx, double dy, int height);
  void zoomPixels(double dy, int height);  // drag down zooms out
  void zoomWheel(double clicks);           // positive (wheel away from the user) zooms in

  static constexpr double kMaxElevation = 1.55;  // radians (~88.8 degrees)

 private:
  scene::Camera home_, cam_;
};

}  // namespace sm::view
