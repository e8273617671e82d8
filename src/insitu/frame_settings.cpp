#include "frame_settings.h"

#include <cmath>

#include "common/error.h"
#include "common/hash.h"
#include "common/setting_error.h"
#include "session/setting_names.h"

namespace sm::insitu {
namespace {

namespace api = shellmarch::insitu;

glm::dvec3 vec(const std::array<double, 3>& a) {
  return {a[0], a[1], a[2]};
}

// What only the API has: its strings and the legend's colour; a given range is checked here too,
// before the ranks reduce the field's own.
void checkApiFields(const api::RenderSettings& s) {
  if (s.range && !(std::isfinite((*s.range)[0]) && std::isfinite((*s.range)[1]) &&
                   (*s.range)[0] <= (*s.range)[1]))
    throw SettingError("range", "[", (*s.range)[0], ", ", (*s.range)[1],
                       "] must be finite with lo <= hi");
  if (!std::isfinite(s.unitDistance))
    throw SettingError("unit-distance", s.unitDistance, " must be finite (0 or less: the default)");
  if (!std::isfinite(s.sampleDistance))
    throw SettingError("step", s.sampleDistance, " must be finite (0 or less: the default)");
  for (float c : s.legendBackground)
    if (!(c >= 0.0f && c <= 1.0f))
      throw SettingError("legend-background", "components must be in [0, 1], not ", c);
  if (s.integration != "exact" && s.integration != "sampled")
    throw SettingError("integration", "'", s.integration, "' is not exact or sampled");
}

}  // namespace

session::FrameRequest frameRequest(const api::RenderSettings& s) {
  checkApiFields(s);
  session::FrameRequest r;
  r.width = s.width;
  r.height = s.height;
  r.view = s.view;
  if (s.camera) {
    r.eye = vec(s.camera->eye);
    r.at = vec(s.camera->at);
    r.up = vec(s.camera->up);
    r.fovyDeg = s.camera->fovyDeg;
  }
  r.colormap = s.colormap;
  for (const auto& e : s.table) r.table.emplace_back(e[0], e[1], e[2], e[3]);
  r.logScale = s.logScale;
  r.opacityScale = s.opacityScale;
  if (s.unitDistance > 0) r.unitDistance = s.unitDistance;
  if (s.sampleDistance > 0) r.step = s.sampleDistance;
  r.integration =
      s.integration == "sampled" ? render::Integration::Sampled : render::Integration::ElementExact;
  r.earlyTermination = s.earlyTermination;
  for (const api::ClipPlane& c : s.clipPlanes)
    r.clipPlanes.push_back({vec(c.point), vec(c.normal)});
  return r;
}

session::DataExtent dataExtent(const MeshFrame& frame) {
  return {frame.whole, frame.meanElementSize, "the mesh"};
}

void inApiTerms(const std::function<void()>& f) {
  try {
    f();
  } catch (const SettingError& e) {
    throw Error("render: ", session::apiMessage(e));
  }
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
