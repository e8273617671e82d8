#include "session/frame_request.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "common/setting_error.h"
#include "render/step_limits.h"
#include "scene/view_defaults.h"

namespace sm::session {
namespace {

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void checkPoint(const std::optional<glm::dvec3>& p, const char* key) {
  if (p && !finite(*p)) throw SettingError(key, p->x, ",", p->y, ",", p->z, " is not finite");
}

scene::TransferFunction colours(const FrameRequest& r) {
  if (r.table.empty()) return scene::makeTransferFunction(r.colormap);
  if (r.table.size() < 2) throw SettingError("table", "has one entry; it needs at least 2");
  scene::TransferFunction tf;
  for (const glm::vec4& e : r.table)
    for (int c = 0; c < 4; ++c)
      if (!(e[c] >= 0.0f && e[c] <= 1.0f))
        throw SettingError("table", "entries must be in [0, 1], not ", e[c]);
  tf.table = r.table;
  return tf;
}

// The step when none is given comes from the mesh: a fault then lies with the mesh or the view,
// not with a setting the user did not give.
double defaultStep(const DataExtent& data, const glm::dvec3& eye) {
  const double dt = scene::defaultStep(data.meanElementSize, data.whole);
  if (!(dt > 0))
    throw Error(data.name, ": every element has zero volume: there is no volume to render");
  if (const double finest = render::finestStep(eye, data.whole); dt < finest)
    throw SettingError("step", "the default sample step ", dt,
                       " (half the mean element size, at most the diagonal / 256) is finer than ",
                       "float distances along a ray resolve this far from the data (up to ",
                       finest * 0x1p24, "): move the eye closer or give a step of at least ",
                       finest);
  return dt;
}

}  // namespace

void checkRequest(const FrameRequest& r) {
  if (r.width <= 0 || r.height <= 0 || r.width > 16384 || r.height > 16384)
    throw SettingError("size", r.width, "x", r.height,
                       " is not a usable image size (1 .. 16384 per side)");
  checkPoint(r.eye, "eye");
  checkPoint(r.at, "at");
  checkPoint(r.up, "up");
  if (r.unitDistance && !(*r.unitDistance > 0 && std::isfinite(*r.unitDistance)))
    throw SettingError("unit-distance", *r.unitDistance, " must be positive and finite");
  if (r.step && !(*r.step > 0 && std::isfinite(*r.step)))
    throw SettingError("step", "the sample distance must be positive and finite, not ", *r.step);
  if (!(r.opacityScale >= 0 && std::isfinite(r.opacityScale)))
    throw SettingError("opacity-scale", r.opacityScale, " must be finite and not negative");
  if (!(r.earlyTermination > 0 && std::isfinite(r.earlyTermination)))
    throw SettingError("early-termination", r.earlyTermination, " must be positive and finite");
}

scene::TransferFunction makeTransferFunction(const FrameRequest& r, const std::string& field,
                                             std::pair<double, double> range) {
  scene::TransferFunction tf = colours(r);
  tf.lo = range.first;
  tf.hi = range.second;
  if (r.logScale) {
    tf.scale = scene::ScalarScale::Log;
    if (!(range.first > 0))
      throw SettingError("log-scale", "field '", field, "' has the range ", range.first, " .. ",
                         range.second,
                         ", and a log scale needs a positive one: give a range LO,HI with "
                         "0 < LO < HI");
  }
  if (!r.opacityPoints.empty()) scene::setOpacityPoints(tf, r.opacityPoints);
  if (r.nanColor) {
    tf.nanColor = glm::vec3(*r.nanColor);
    tf.nanOpacity = r.nanColor->a;
  }
  tf.opacityScale = r.opacityScale;
  return tf;
}

scene::Camera makeCamera(const FrameRequest& r, const mesh::Bounds& whole) {
  const double aspect = double(r.width) / r.height;
  scene::Camera c;
  if (!r.eye) {
    if (r.at || r.up) throw SettingError("eye", "--at and --up need it (or use --view)");
    c = scene::frameBounds(
        whole, scene::parseViewPreset(r.view), aspect, r.fovyDeg,
        r.parallel ? scene::Projection::Parallel : scene::Projection::Perspective);
  } else {
    c.eye = *r.eye;
    c.at = r.at.value_or(whole.center());
    if (!r.at && c.eye == c.at)
      throw SettingError("eye", c.eye.x, ",", c.eye.y, ",", c.eye.z,
                         " is the centre of the data, where the camera looks without --at: give "
                         "--at");
    c.up = r.up.value_or(scene::defaultUp(c.at - c.eye));
    c.fovyDeg = r.fovyDeg;
    c.parallel = r.parallel;
    c.parallelScale = scene::fitParallelScale(whole, aspect);
  }
  if (r.parallelScale) c.parallelScale = *r.parallelScale;
  scene::cameraFrame(c, r.width, r.height);  // refuses a camera it cannot frame, naming why
  return c;
}

render::RenderSettings makeRenderSettings(const FrameRequest& r, const DataExtent& data,
                                          const std::string& field,
                                          std::pair<double, double> range) {
  checkRequest(r);
  render::RenderSettings s;
  s.width = r.width;
  s.height = r.height;
  s.camera = makeCamera(r, data.whole);
  scene::TransferFunction& tf = s.transferFunction;
  tf = makeTransferFunction(r, field, range);
  tf.unitDistance = r.unitDistance.value_or(scene::defaultUnitDistance(data.whole));
  if (!(tf.unitDistance > 0))
    throw SettingError("unit-distance", "the data set is flat (zero volume): give one");
  s.dt = r.step ? *r.step : defaultStep(data, s.camera.eye);
  // Checked against the whole data set, so that every rank refuses the step alike.
  render::checkStep(s.dt, s.camera.eye, data.whole);
  // Element-exact integration takes no samples (the step only bounds the pieces of non-linear
  // cells), so a step beyond the data is harmless there.
  s.integration = r.integration;
  if (s.integration == render::Integration::Sampled)
    render::checkStepNotBeyondData(s.dt, data.whole);
  s.earlyTermination = r.earlyTermination;
  s.shading = r.shading;
  render::checkShading(s.shading);
  scene::checkClipPlanes(r.clipPlanes);
  s.clipPlanes = r.clipPlanes;
  s.allTypePipelines = r.allTypePipelines;
  return s;
}

}  // namespace sm::session
