// A frame as a front end asks for it, in neutral terms: the command line (RenderJob), the viewer,
// the in-situ API and the Python module each fill one, and makeRenderSettings turns it into the
// renderer's settings in this one place, with the defaults that depend on the whole data set and
// every check. Errors are SettingErrors keyed by the setting (common/setting_error.h), which each
// front end shows by its own name for it.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "mesh/bounds.h"
#include "render/render_settings.h"
#include "scene/clip_plane.h"
#include "scene/transfer_function.h"

namespace sm::session {

struct FrameRequest {
  int width = 512, height = 512;
  // The camera: an eye (with at and up, or their defaults), or else a view preset framing the
  // whole data set.
  std::string view = "iso";
  std::optional<glm::dvec3> eye, at, up;
  double fovyDeg = 30.0;
  bool parallel = false;
  std::optional<double> parallelScale;  // unset: the data's bounding sphere fits
  // The transfer function: a colour map by name (or file), or an explicit RGBA table (>= 2
  // entries in [0, 1]) that replaces it.
  std::string colormap = "viridis";
  std::vector<glm::vec4> table;
  std::vector<scene::OpacityPoint> opacityPoints;  // in data values; empty: the map's own
  bool logScale = false;
  std::optional<glm::vec4> nanColor;  // unset: the colour map's
  double opacityScale = 1.0;
  std::optional<double> unitDistance, step;  // unset: from the data (scene/view_defaults.h)
  render::Integration integration = render::Integration::ElementExact;
  double earlyTermination = 0.99;
  render::Shading shading;
  std::vector<scene::ClipPlane> clipPlanes;
  bool allTypePipelines = false;  // benchmarks only
};

// What the defaults and checks take from the whole data set, the same on every rank (so that
// every rank refuses a setting alike).
struct DataExtent {
  mesh::Bounds whole;
  double meanElementSize = 0;
  std::string name;  // the data set, for messages about it (a file name, "the mesh")
};

// Checks what needs no data: image size, finite numbers, integration and early termination.
void checkRequest(const FrameRequest& r);

// The renderer's settings for `r` over `data`, the transfer function mapping `range` of `field`
// (named in messages): checkRequest, then the camera, the transfer function, the sample step and
// the unit distance, each checked.
render::RenderSettings makeRenderSettings(const FrameRequest& r, const DataExtent& data,
                                          const std::string& field,
                                          std::pair<double, double> range);

// The transfer function of `r` over `range` of `field` (named in messages): the colour map or
// table, the scale (a log scale needs a positive range), opacity points, NaN colour and opacity
// scale. The unit distance is makeRenderSettings's (it needs the data set).
scene::TransferFunction makeTransferFunction(const FrameRequest& r, const std::string& field,
                                             std::pair<double, double> range);

// The camera of `r` over the whole data set `whole`.
scene::Camera makeCamera(const FrameRequest& r, const mesh::Bounds& whole);

}  // namespace sm::session
