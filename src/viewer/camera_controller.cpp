#include "viewer/camera_controller.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "common/error.h"

namespace sm::view {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

CameraController::CameraController(const scene::Camera& home) : home_(home), cam_(home) {
  scene::cameraFrame(home, 1, 1);  // throws on a degenerate camera, before any interaction
}

double CameraController::distance() const {
  return glm::length(cam_.eye - cam_.at);
}

void CameraController::orbit(double yawRad, double elevationRad) {
  const glm::dvec3 up = glm::normalize(cam_.up);
  glm::dvec3 offset = cam_.eye - cam_.at;
  const double d = glm::length(offset);
  // The eye sits at -d * forward; rotating the offset right-handedly about up moves it towards
  // forward x up, the camera's right (scene::turnAbout, without the round trip through `at`).
  offset = scene::rotateAbout(offset, up, yawRad);
  const double vertical = glm::dot(offset, up);
  const glm::dvec3 horizontal = offset - vertical * up;
  const double h = glm::length(horizontal);
  if (h > 0) {
    double e = std::atan2(vertical, h) + elevationRad;
    e = std::clamp(e, -kMaxElevation, kMaxElevation);
    offset = d * (std::cos(e) * (horizontal / h) + std::sin(e) * up);
  }
  cam_.eye = cam_.at + offset;
}

void CameraController::pan(double right, double up) {
  scene::CameraFrame f = scene::cameraFrame(cam_, 1, 1);
  const glm::dvec3 move = f.right * right + f.upOrtho * up;
  cam_.eye += move;
  cam_.at += move;
}

void CameraController::zoom(double factor) {
  if (!(factor > 0) || !std::isfinite(factor)) return;
  if (cam_.parallel) {
    const double scale = cam_.parallelScale * factor;
    if (scale > 0 && scale < 1e30) cam_.parallelScale = scale;
    return;
  }
  const glm::dvec3 offset = (cam_.eye - cam_.at) * factor;
  if (!(glm::length(offset) > 0)) return;  // never collapse onto `at`
  cam_.eye = cam_.at + offset;
}

void CameraController::toggleProjection() {
  const double tanHalf = std::tan(glm::radians(cam_.fovyDeg) * 0.5);
  if (!cam_.parallel) {
    cam_.parallelScale = distance() * tanHalf;
    cam_.parallel = true;
    return;
  }
  const glm::dvec3 offset = cam_.eye - cam_.at;
  const double d = glm::length(offset);
  if (d > 0) cam_.eye = cam_.at + offset * (cam_.parallelScale / tanHalf / d);
  cam_.parallel = false;
}

void CameraController::orbitPixels(double dx, double dy, int height) {
  // A drag over the window's height turns the view by half a turn.
  const double perPixel = kPi / std::max(height, 1);
  orbit(-dx * perPixel, dy * perPixel);
}

void CameraController::panPixels(double dx, double dy, int height) {
  // World units per pixel on the plane through `at` facing the camera.
  const double halfHeight =
      cam_.parallel ? cam_.parallelScale : distance() * std::tan(glm::radians(cam_.fovyDeg) * 0.5);
  const double perPixel = 2.0 * halfHeight / std::max(height, 1);
  pan(-dx * perPixel, dy * perPixel);
}

void CameraController::zoomPixels(double dy, int height) {
  zoom(std::exp(2.0 * dy / std::max(height, 1)));
}

void CameraController::zoomWheel(double clicks) {
  zoom(std::pow(0.9, clicks));
}

}  // namespace sm::view
