#include "frame_settings.h"

#include <cmath>
#include <string_view>

#include <glm/geometric.hpp>

#include "common/error.h"
#include "common/hash.h"
#include "render/frame_defaults.h"

namespace sm::insitu {
namespace {

namespace api = shellmarch::insitu;

glm::dvec3 vec(const std::array<double, 3>& a) {
  return {a[0], a[1], a[2]};
}

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The scene module's checks name command-line options; these name the API's fields.
scene::Camera camera(const api::RenderSettings& s, const mesh::Bounds& whole) {
  if (!s.camera) {
    scene::ViewPreset preset;
    try {
      preset = scene::parseViewPreset(s.view);
    } catch (const Error&) {
      throw Error("render: view '", s.view, "' is not one of iso, +x, -x, +y, -y, +z, -z");
    }
    return scene::frameBounds(whole, preset, double(s.width) / s.height);
  }
  scene::Camera c{vec(s.camera->eye), vec(s.camera->at), vec(s.camera->up), s.camera->fovyDeg};
  if (!finite(c.eye) || !finite(c.at) || !finite(c.up))
    throw Error("render: camera eye, at and up must be finite");
  if (!(c.fovyDeg > 0 && c.fovyDeg < 180))
    throw Error("render: camera fovyDeg ", c.fovyDeg, " is not in (0, 180)");
  if (c.eye == c.at) throw Error("render: camera eye and at are the same point");
  glm::dvec3 side = glm::cross(glm::normalize(c.at - c.eye), c.up);
  if (!(glm::length(side) >= 1e-12 * glm::length(c.up)) || glm::length(c.up) == 0)
    throw Error("render: camera up is zero or parallel to the viewing direction");
  return c;
}

scene::TransferFunction transferFunction(const api::RenderSettings& s) {
  scene::TransferFunction tf;
  if (s.table.empty()) {
    try {
      tf = scene::makeTransferFunction(s.colormap);
    } catch (const Error& e) {
      std::string_view why = e.what();
      if (why.starts_with("--colormap: ")) why.remove_prefix(12);  // the option is ours here
      throw Error("render: colormap: ", why);
    }
  } else {
    if (s.table.size() < 2) throw Error("render: table has one entry; it needs at least 2");
    for (const auto& e : s.table) {
      for (float c : e)
        if (!(c >= 0.0f && c <= 1.0f))
          throw Error("render: table entries must be in [0, 1], not ", c);
      tf.table.emplace_back(e[0], e[1], e[2], e[3]);
    }
  }
  if (!(s.opacityScale >= 0 && std::isfinite(s.opacityScale)))
    throw Error("render: opacityScale must be finite and not negative, not ", s.opacityScale);
  tf.opacityScale = s.opacityScale;
  tf.scale = s.logScale ? scene::ScalarScale::Log : scene::ScalarScale::Linear;
  return tf;
}

void checkBasics(const api::RenderSettings& s) {
  if (s.width <= 0 || s.height <= 0 || s.width > 16384 || s.height > 16384)
    throw Error("render: image size ", s.width, "x", s.height, " is not in 1 .. 16384 per side");
  if (s.range && !(std::isfinite((*s.range)[0]) && std::isfinite((*s.range)[1]) &&
                   (*s.range)[0] <= (*s.range)[1]))
    throw Error("render: range [", (*s.range)[0], ", ", (*s.range)[1],
                "] must be finite with lo <= hi");
  for (double v : {s.unitDistance, s.sampleDistance, s.earlyTermination})
    if (!std::isfinite(v))
      throw Error("render: unitDistance, sampleDistance and earlyTermination must be finite");
  for (float c : s.legendBackground)
    if (!(c >= 0.0f && c <= 1.0f))
      throw Error("render: legendBackground components must be in [0, 1], not ", c);
  if (!(s.earlyTermination > 0))
    throw Error("render: earlyTermination ", s.earlyTermination, " must be positive");
  if (s.integration != "exact" && s.integration != "sampled")
    throw Error("render: integration '", s.integration, "' (use exact or sampled)");
}

}  // namespace

render::RenderSettings toRenderSettings(const api::RenderSettings& s, const MeshFrame& frame) {
  checkBasics(s);
  render::RenderSettings r;
  r.width = s.width;
  r.height = s.height;
  r.camera = camera(s, frame.whole);
  r.transferFunction = transferFunction(s);
  r.transferFunction.unitDistance =
      s.unitDistance > 0 ? s.unitDistance : render::defaultUnitDistance(frame.whole);
  r.dt = s.sampleDistance > 0 ? s.sampleDistance
                              : render::defaultStep(frame.meanElementSize, frame.whole);
  if (!(r.dt > 0 && r.transferFunction.unitDistance > 0))
    throw Error("render: the mesh is flat (zero volume); give sampleDistance and unitDistance");
  // Here, with the whole mesh's bounds, so that every rank refuses it alike (an agreed error).
  render::checkStep(r.dt, r.camera.eye, frame.whole, "render: sampleDistance");
  r.integration =
      s.integration == "sampled" ? render::Integration::Sampled : render::Integration::ElementExact;
  // Element-exact integration takes no samples (the step only bounds its pieces), as the command
  // line's check.
  if (r.integration == render::Integration::Sampled)
    render::checkStepNotBeyondData(r.dt, frame.whole, "render: sampleDistance");
  r.earlyTermination = s.earlyTermination;
  for (const api::ClipPlane& c : s.clipPlanes)
    r.clipPlanes.push_back(
        {{c.point[0], c.point[1], c.point[2]}, {c.normal[0], c.normal[1], c.normal[2]}});
  scene::checkClipPlanes(r.clipPlanes, "render: clipPlanes");
  return r;
}

uint64_t settingsDigest(const api::RenderSettings& s) {
  Hasher h;
  h.pod(s.width).pod(s.height).str(s.field).str(s.view).str(s.colormap);
  h.pod(s.camera.has_value());
  if (s.camera) h.pod(s.camera->eye).pod(s.camera->at).pod(s.camera->up).pod(s.camera->fovyDeg);
  h.span(std::span<const std::array<float, 4>>(s.table));
  h.pod(s.range.has_value());
  if (s.range) h.pod(*s.range);
  h.pod(s.logScale)
      .pod(s.opacityScale)
      .pod(s.unitDistance)
      .pod(s.sampleDistance)
      .str(s.integration)
      .pod(s.earlyTermination);
  h.pod(s.clipPlanes.size());
  for (const api::ClipPlane& c : s.clipPlanes) h.pod(c.point).pod(c.normal);
  h.pod(s.legend).pod(s.legendBackground);
  return h.digest();
}

}  // namespace sm::insitu
