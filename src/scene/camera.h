// The camera every renderer in shellmarch uses (GPU, CPU reference, viewer): a pinhole, or a
// parallel (orthographic) projection as ParaView's. A pixel's ray is defined here once, so images
// from different renderers are comparable pixel for pixel.
#pragma once

#include <string>

#include <glm/vec3.hpp>

#include "mesh/bounds.h"

namespace sm::scene {

// `up` need not be orthogonal to the viewing direction (only not parallel to it): the frame
// takes its part orthogonal to it. The default camera looks down -z, so its up is +y.
struct Camera {
  glm::dvec3 eye{0, 0, 1}, at{0, 0, 0}, up{0, 1, 0};
  double fovyDeg = 30.0;       // perspective: the vertical field of view
  bool parallel = false;       // parallel projection: every ray runs along the viewing direction
  double parallelScale = 1.0;  // parallel: half the image's height in world units (ParaView's)
};

enum class Projection { Perspective, Parallel };

// The up vector a camera takes when none is given: +z, or +y when it looks along z (within a
// degree), where +z would be (nearly) parallel to the viewing direction.
glm::dvec3 defaultUp(const glm::dvec3& viewDirection);

enum class ViewPreset { Iso, PosX, NegX, PosY, NegY, PosZ, NegZ };
ViewPreset parseViewPreset(const std::string& s);  // "iso", "+x", ...; throws sm::Error

// A camera looking at the bounds' centre from the preset direction, far enough that the bounding
// sphere fits the smaller of the two fields of view. "+x" looks along +x (eye on the -x side); up
// is defaultUp's: +z, and +y for the views along z. A parallel camera sits at the same place (in
// front of all the data) with fitParallelScale's scale.
Camera frameBounds(const mesh::Bounds& b, ViewPreset view, double aspect, double fovyDeg = 30.0,
                   Projection projection = Projection::Perspective);
// The parallel scale at which the bounds' bounding sphere (with frameBounds' 2% margin) fits both
// the image's height and its width.
double fitParallelScale(const mesh::Bounds& b, double aspect);

// Orthonormal frame and image plane of a camera for a W x H image.
//   pixel (x, y), y = 0 the top row:  u = (2 (x + 0.5) / W - 1) * halfHeight * W / H
//                                     v = (1 - 2 (y + 0.5) / H) * halfHeight
//   perspective: halfHeight = tan(fovy / 2),
//                direction = normalize(forward + u * right + v * upOrtho), origin = eye;
//   parallel:    halfHeight = parallelScale,
//                direction = forward, origin = eye + u * right + v * upOrtho.
// Distances along a ray (t) are therefore world-space distances from the eye, or with a parallel
// projection from the plane through the eye facing the camera (data behind that plane is not seen).
struct CameraFrame {
  glm::dvec3 eye, forward, right, upOrtho;
  double halfHeight, aspect;
  bool parallel;
  int width, height;
  // px, py: pixel coordinates of the sample
  glm::dvec3 origin(double px, double py) const;
  glm::dvec3 direction(double px, double py) const;
  glm::dvec3 pixelOrigin(int x, int y) const { return origin(x + 0.5, y + 0.5); }
  glm::dvec3 pixelDirection(int x, int y) const { return direction(x + 0.5, y + 0.5); }
};
CameraFrame cameraFrame(const Camera& c, int width, int height);  // throws on degenerate cameras

// Rodrigues' rotation of v about the unit axis k by angle a (radians, right-handed).
glm::dvec3 rotateAbout(const glm::dvec3& v, const glm::dvec3& k, double a);
// The camera turned about its up axis through `at` by `angleRad`: positive moves the eye towards
// the camera's right (counter-clockwise seen from above); `at`, `up`, the field of view and the
// distance to `at` and the projection are unchanged. A turntable step, as the viewer's drag and
// `render --orbit` make.
Camera turnAbout(const Camera& c, double angleRad);

}  // namespace sm::scene
