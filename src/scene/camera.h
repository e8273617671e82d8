// The pinhole camera every renderer in shellmarch uses (GPU, CPU reference, viewer). A pixel's ray
// is defined here once, so images from different renderers are comparable pixel for pixel.
#pragma once

#include <string>

#include <glm/vec3.hpp>

#include "mesh/unstructured_mesh.h"

namespace sm::scene {

struct Camera {
  glm::dvec3 eye{0, 0, 1}, at{0, 0, 0}, up{0, 1, 0};
  double fovyDeg = 30.0;
};

enum class ViewPreset { Iso, PosX, NegX, PosY, NegY, PosZ, NegZ };
ViewPreset parseViewPreset(const std::string& s);  // "iso", "+x", ...; throws sm::Error

// A camera looking at the bounds' centre from the preset direction, far enough that the bounding
// sphere fits the smaller of the two fields of view. "+x" looks along +x (eye on the -x side).
Camera frameBounds(const mesh::Bounds& b, ViewPreset view, double aspect, double fovyDeg = 30.0);

// Orthonormal frame and image plane of a camera for a W x H image.
//   pixel (x, y), y = 0 the top row:  u = (2 (x + 0.5) / W - 1) * tan(fovy / 2) * W / H
//                                     v = (1 - 2 (y + 0.5) / H) * tan(fovy / 2)
//   direction = normalize(forward + u * right + v * upOrtho); origin = eye.
// Distances along a ray (t) are therefore world-space distances from the eye.
struct CameraFrame {
  glm::dvec3 eye, forward, right, upOrtho;
  double tanHalfFovy, aspect;
  int width, height;
  glm::dvec3 direction(double px, double py) const;  // px, py: pixel coordinates of the sample
  glm::dvec3 pixelDirection(int x, int y) const { return direction(x + 0.5, y + 0.5); }
};
CameraFrame cameraFrame(const Camera& c, int width, int height);  // throws on degenerate cameras

// Rodrigues' rotation of v about the unit axis k by angle a (radians, right-handed).
glm::dvec3 rotateAbout(const glm::dvec3& v, const glm::dvec3& k, double a);
// The camera turned about its up axis through `at` by `angleRad`: positive moves the eye towards
// the camera's right (counter-clockwise seen from above); `at`, `up`, the field of view and the
// distance to `at` are unchanged. A turntable step, as the viewer's drag and `render --orbit` make.
Camera turnAbout(const Camera& c, double angleRad);

}  // namespace sm::scene
