#include "scene/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "common/error.h"
#include "common/setting_error.h"

namespace sm::scene {

ViewPreset parseViewPreset(const std::string& s) {
  if (s == "iso") return ViewPreset::Iso;
  if (s == "+x") return ViewPreset::PosX;
  if (s == "-x") return ViewPreset::NegX;
  if (s == "+y") return ViewPreset::PosY;
  if (s == "-y") return ViewPreset::NegY;
  if (s == "+z") return ViewPreset::PosZ;
  if (s == "-z") return ViewPreset::NegZ;
  throw SettingError("view", "unknown view '", s, "' (use iso, +x, -x, +y, -y, +z or -z)");
}

glm::dvec3 defaultUp(const glm::dvec3& viewDirection) {
  const double len = glm::length(viewDirection);
  // sin(1 degree): closer to z than that, +z would make a badly conditioned frame.
  if (len > 0 && glm::length(glm::cross(viewDirection / len, glm::dvec3(0, 0, 1))) < 0.0174524)
    return {0, 1, 0};
  return {0, 0, 1};
}

namespace {

std::string point(const glm::dvec3& p) {
  return concat(p.x, ",", p.y, ",", p.z);
}

double boundingRadius(const mesh::Bounds& b) {
  return std::max(0.5 * b.diagonal(), 1e-30);
}

}  // namespace

Camera frameBounds(const mesh::Bounds& b, ViewPreset view, double aspect, double fovyDeg,
                   Projection projection) {
  glm::dvec3 dir(0.0);
  switch (view) {
    case ViewPreset::Iso:
      dir = glm::normalize(glm::dvec3(-1, -1.3, -0.8));
      break;
    case ViewPreset::PosX:
      dir = {1, 0, 0};
      break;
    case ViewPreset::NegX:
      dir = {-1, 0, 0};
      break;
    case ViewPreset::PosY:
      dir = {0, 1, 0};
      break;
    case ViewPreset::NegY:
      dir = {0, -1, 0};
      break;
    case ViewPreset::PosZ:
      dir = {0, 0, 1};
      break;
    case ViewPreset::NegZ:
      dir = {0, 0, -1};
      break;
  }
  Camera c;
  c.fovyDeg = fovyDeg;
  c.at = b.empty ? glm::dvec3(0.0) : b.center();
  double halfY = glm::radians(fovyDeg) * 0.5;
  double halfX = std::atan(std::tan(halfY) * aspect);
  double half = std::min(halfX, halfY);
  double dist = boundingRadius(b) / std::sin(half) * 1.02;
  c.eye = c.at - dir * dist;
  c.up = defaultUp(dir);
  if (projection == Projection::Parallel) {
    c.parallel = true;
    c.parallelScale = fitParallelScale(b, aspect);
  }
  return c;
}

double fitParallelScale(const mesh::Bounds& b, double aspect) {
  // The half height must hold the radius, and so must the half width, halfHeight * aspect.
  return boundingRadius(b) * 1.02 * std::max(1.0, 1.0 / aspect);
}

CameraFrame cameraFrame(const Camera& c, int width, int height) {
  if (width <= 0 || height <= 0) throw Error("image size ", width, "x", height, " is empty");
  if (!(c.fovyDeg > 0.0 && c.fovyDeg < 180.0))
    throw SettingError("fovy", c.fovyDeg, " degrees is not in (0, 180)");
  if (c.parallel && !(c.parallelScale > 0.0 && c.parallelScale < 1e30))
    throw SettingError("parallel-scale", c.parallelScale, " is not a positive length below 1e30");
  glm::dvec3 f = c.at - c.eye;
  if (glm::length(f) == 0.0)
    throw SettingError("at", point(c.at), " is the eye's position: the camera looks nowhere");
  f = glm::normalize(f);
  glm::dvec3 r = glm::cross(f, c.up);
  if (glm::length(c.up) == 0.0) throw SettingError("up", point(c.up), " is the zero vector");
  if (glm::length(r) < 1e-12 * glm::length(c.up))
    throw SettingError("up", point(c.up), " is parallel to the viewing direction");
  r = glm::normalize(r);
  CameraFrame fr;
  fr.eye = c.eye;
  fr.forward = f;
  fr.right = r;
  fr.upOrtho = glm::cross(r, f);
  fr.parallel = c.parallel;
  fr.halfHeight = c.parallel ? c.parallelScale : std::tan(glm::radians(c.fovyDeg) * 0.5);
  fr.aspect = double(width) / double(height);
  fr.width = width;
  fr.height = height;
  return fr;
}

glm::dvec3 CameraFrame::origin(double px, double py) const {
  if (!parallel) return eye;
  double u = (2.0 * px / width - 1.0) * halfHeight * aspect;
  double v = (1.0 - 2.0 * py / height) * halfHeight;
  return eye + u * right + v * upOrtho;
}

glm::dvec3 CameraFrame::direction(double px, double py) const {
  if (parallel) return forward;
  double u = (2.0 * px / width - 1.0) * halfHeight * aspect;
  double v = (1.0 - 2.0 * py / height) * halfHeight;
  return glm::normalize(forward + u * right + v * upOrtho);
}

glm::dvec3 rotateAbout(const glm::dvec3& v, const glm::dvec3& k, double a) {
  return v * std::cos(a) + glm::cross(k, v) * std::sin(a) + k * glm::dot(k, v) * (1 - std::cos(a));
}

Camera turnAbout(const Camera& c, double angleRad) {
  Camera turned = c;
  // The eye sits at -d * forward; turning the offset right-handedly about up moves it towards
  // forward x up, the camera's right.
  turned.eye = c.at + rotateAbout(c.eye - c.at, glm::normalize(c.up), angleRad);
  return turned;
}

}  // namespace sm::scene
