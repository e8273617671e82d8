// The `shellmarch render` arguments that give the frame the viewer shows (the report's
// render_args, --print-camera): how a user turns a view into a PNG at any size, and how the tests
// check that the viewer shows what render draws.
#pragma once

#include <string>
#include <vector>

#include "scene/clip_plane.h"
#include "scene/transfer_function.h"
#include "viewer/view_scene.h"
#include "viewer/view_state.h"

namespace sm::view {

// What the frame was drawn with, besides the state: the field shown, the colour map's name, the
// transfer function (its scale and unit distance), the opacity points when they applied to this
// frame's field (else empty), the planes it was clipped by (the view's --clip planes and the cut),
// whether the legend was drawn, and the integration (--integration sampled when not the default).
struct FrameLook {
  const FieldInfo& field;
  const std::string& colormap;
  const scene::TransferFunction& transferFunction;
  const std::vector<scene::OpacityPoint>& opacityPoints;
  const std::vector<scene::ClipPlane>& clipPlanes;
  bool legend = false;
  bool sampled = false;
};

// Every number exact (%.17g), so that render draws the same frame bit for bit.
std::vector<std::string> renderArgs(const ViewState& state, int width, int height,
                                    const FrameLook& look);

// "%.17g" and the like, as a string.
std::string formatNumber(const char* format, double v);

}  // namespace sm::view
