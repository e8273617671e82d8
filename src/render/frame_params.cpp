#include "render/frame_params.h"

#include <cmath>
#include <span>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "common/error.h"
#include "common/setting_error.h"
#include "render/step_limits.h"

namespace sm::render {
namespace {

glm::vec3 toFloat(const glm::dvec3& v) {
  return glm::vec3(v);
}

// Whether box b reaches within `pad` of the plane through `point` with unit normal `normal`.
bool boxMeetsPlane(const mesh::Bounds& b, const glm::dvec3& point, const glm::dvec3& normal,
                   double pad) {
  const glm::dvec3 c = b.center() - point, half = 0.5 * (b.hi - b.lo);
  return std::abs(glm::dot(c, normal)) <= glm::dot(half, glm::abs(normal)) + pad;
}

void setCamera(const scene::CameraFrame& cam, const GpuScene& scene, bool explicitRays,
               gpu::FrameParams& p) {
  // Device lengths are world lengths times scene.scale() (1 for data sets of ordinary size).
  const double scale = scene.scale();
  const glm::dvec3 eye = scene.toDevice(cam.eye);
  // Rays can only start inside the volume when the eye is within this rank's bounds (padded for
  // rounding); elsewhere the traversal skips the query that looks for such a start.
  const mesh::Bounds& b = scene.rebasedBounds();
  const glm::dvec3 pad(1e-3 * b.diagonal() + 1e-30);
  bool inBounds = !b.empty && glm::all(glm::greaterThanEqual(eye, b.lo - pad)) &&
                  glm::all(glm::lessThanEqual(eye, b.hi + pad));
  // Parallel rays start anywhere on the plane through the eye: they may start inside when the
  // box reaches that plane.
  if (cam.parallel && !b.empty) inBounds = boxMeetsPlane(b, eye, cam.forward, pad.x);
  p.eyeMayBeInside = (explicitRays || inBounds) ? 1u : 0u;
  p.boundsValid = b.empty ? 0u : 1u;
  if (!b.empty) {
    p.boundsLo = glm::vec3(b.lo);
    p.boundsHi = glm::vec3(b.hi);
  }
  p.eye = toFloat(eye);
  p.forward = toFloat(cam.forward);
  p.right = toFloat(cam.right);
  p.upOrtho = toFloat(cam.upOrtho);
  // A parallel scale is a length: device lengths are world lengths times the scale.
  p.halfHeight = float(cam.parallel ? cam.halfHeight * scale : cam.halfHeight);
  p.parallel = cam.parallel ? 1u : 0u;
  p.aspect = float(cam.aspect);
}

void setTransferFunction(const scene::TransferFunction& tf, double scale, gpu::FrameParams& p) {
  if (tf.hi > tf.lo && tf.scale == scene::ScalarScale::Log) {  // the shader maps log2(s)
    p.tfLo = float(std::log2(tf.lo));
    p.tfScale = float(1.0 / std::log2(tf.hi / tf.lo));
  } else if (tf.hi > tf.lo) {
    p.tfLo = float(tf.lo);
    p.tfScale = float(1.0 / (tf.hi - tf.lo));
  } else {  // constant range: every entry of the device's table is the middle (FrameResources)
    p.tfLo = float(tf.lo);
    p.tfScale = 1.0f;
  }
  p.tfEntries = uint32_t(tf.table.size());
  p.sigmaScale = float(tf.opacityScale / (tf.unitDistance * scale));
  p.nanColor = glm::vec4(tf.nanColor, tf.nanOpacity);
}

void setShading(const Shading& sh, gpu::FrameParams& p) {
  checkShading(sh);
  if (!sh.enabled) return;
  p.shadeAmbient = float(sh.ambient);
  p.shadeDiffuse = float(sh.diffuse);
  p.shadeSpecular = float(sh.specular);
  p.shadeShininess = float(sh.shininess);
}

// Checks the planes and writes them, in device coordinates, into p.
void setClipPlanes(std::span<const scene::ClipPlane> planes, const GpuScene& scene,
                   gpu::FrameParams& p) {
  static_assert(scene::kMaxClipPlanes == int(gpu::SM_MAX_CLIP_PLANES));
  scene::checkClipPlanes(planes);
  p.clipCount = uint32_t(planes.size());
  for (size_t i = 0; i < planes.size(); ++i) {
    // Device coordinates are rebased and uniformly scaled: the normal keeps its direction, the
    // offset is the rebased point's.
    const glm::dvec3 n = glm::normalize(planes[i].normal);
    const double w = -glm::dot(n, scene.toDevice(planes[i].point));
    if (!(std::abs(w) < 1e30))
      throw Error("clip plane ", i + 1, ": its point is beyond the renderer's float range");
    p.clipPlanes[i] = glm::vec4(glm::vec3(n), float(w));
  }
}

void setPreintegration(const PreintegrationTable& t, VkDeviceAddress table, gpu::FrameParams& p) {
  p.preintegration = table;
  p.piScalarBins = uint32_t(t.scalarBins);
  p.piLengthBins = uint32_t(t.lengthBins);
  p.piSigmaMax = float(t.sigmaMax);
  p.piTauMax = float(t.tauMax);
  p.piCumulative = p.preintegration + t.deviceColorBytes();
  p.piCumulativeBins = uint32_t(t.cumulative.size());
  p.piLo = float(t.lo);
  p.piHi = float(t.hi);
}

}  // namespace

void checkShading(const Shading& sh) {
  if (sh.enabled && !(sh.ambient >= 0 && sh.diffuse >= 0 && sh.specular >= 0 && sh.shininess >= 1 &&
                      sh.shininess <= 1024))
    throw SettingError("shading", "coefficients must be >= 0 and the shininess in [1, 1024], not ",
                       sh.ambient, ",", sh.diffuse, ",", sh.specular, ",", sh.shininess);
}

gpu::FrameParams frameParams(const RenderSettings& s, const GpuScene& scene,
                             const comp::DeepCompositor& compositor,
                             const FrameResources& resources, bool explicitRays) {
  if (s.width != compositor.width() || s.height != compositor.height())
    throw Error("image size ", s.width, "x", s.height, " differs from the compositor's ",
                compositor.width(), "x", compositor.height());
  if (s.transferFunction.table.size() < 2) throw Error("transfer function has no table");
  const scene::CameraFrame cam = scene::cameraFrame(s.camera, s.width, s.height);
  if (!explicitRays)
    checkStep(s.dt * scene.scale(), scene.toDevice(cam.eye), scene.rebasedBounds());
  gpu::FrameParams p{};
  p.scene = scene.refs();
  p.transferFunction = resources.transferFunction();
  p.stats = resources.stats();
  p.rays = explicitRays ? resources.rays() : 0;
  setCamera(cam, scene, explicitRays, p);
  p.width = uint32_t(s.width);
  p.height = uint32_t(s.height);
  p.dt = float(s.dt * scene.scale());
  setTransferFunction(s.transferFunction, scene.scale(), p);
  p.earlyTermination = float(s.earlyTermination);
  setShading(s.shading, p);
  setClipPlanes(s.clipPlanes, scene, p);
  p.maxElementSteps = s.maxElementSteps;
  p.maxSegments = s.maxSegments;
  const comp::DeviceLists lists = compositor.lists();
  p.segCounts = lists.capacities;
  p.segOffsets = lists.offsets;
  p.fragCounts = lists.counts;
  p.fragments = lists.fragments;
  p.fragK = lists.fixedK;
  if (s.integration == Integration::ElementExact)
    setPreintegration(resources.preintegrationTable(), resources.preintegration(), p);
  return p;
}

}  // namespace sm::render
