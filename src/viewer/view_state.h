// The viewer's state for one frame: everything a rank needs to render it. Rank 0 owns it (input
// changes it there) and broadcasts it as plain bytes before every frame, so every rank renders the
// same frame and a quit ends every rank at the same frame.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/camera.h"
#include "scene/clip_plane.h"

namespace sm::view {

// What stops a new field's range pass: the viewer ending, or the user going on to another field
// (ordered: ranks agree on the strongest with a max).
enum class PassInterrupt { None, FieldChange, Quit };

struct ViewState {
  glm::dvec3 eye{0, 0, 1}, at{0, 0, 0}, up{0, 0, 1};
  double fovyDeg = 30.0;
  double opacityScale = 1.0;
  double dt = 0.01;   // sample step along rays
  int32_t width = 0;  // image size = the window's framebuffer size
  int32_t height = 0;
  int32_t renderScale = 1;  // > 1: this frame renders at 1/renderScale of the size (interaction)
  int32_t step = 0;         // time step; ranks wrap it into the field's steps
  int32_t field = 0;        // index into ViewChoices::fields
  int32_t colormap = 0;     // index into ViewChoices::colormaps
  uint32_t playing = 0;     // 1: each frame shows the next step (rank 0 advances it)
  uint32_t frame = 0;       // frames rendered before this one
  uint32_t quit = 0;        // 1: no frame; every rank leaves the loop
  // The view cut (x key): a clip plane through cutPoint keeping the side cutNormal points to, on
  // top of the job's --clip planes.
  uint32_t cut = 0;
  glm::dvec3 cutPoint{0, 0, 0}, cutNormal{0, 0, 1};
  // 1: fields whose range is positive map their logarithm (g key; --log-scale starts with it on).
  uint32_t logScale = 0;
  // 1: parallel projection (p key; --parallel or a parallel --camera file starts with it on),
  // parallelScale half the view's height in world units (the wheel changes it).
  uint32_t parallel = 0;
  double parallelScale = 1.0;

  scene::ClipPlane cutPlane() const { return {cutPoint, cutNormal}; }

  scene::Camera camera() const { return {eye, at, up, fovyDeg, parallel != 0, parallelScale}; }
  void setCamera(const scene::Camera& c) {
    eye = c.eye;
    at = c.at;
    up = c.up;
    fovyDeg = c.fovyDeg;
    parallel = c.parallel ? 1 : 0;
    parallelScale = c.parallelScale;
  }
};
static_assert(std::is_trivially_copyable_v<ViewState>, "broadcast as bytes");

// The size a frame renders at: the window's, or a reduced one while the camera moves.
inline int32_t renderWidth(const ViewState& s) {
  return std::max<int32_t>(1, s.width / std::max<int32_t>(1, s.renderScale));
}
inline int32_t renderHeight(const ViewState& s) {
  return std::max<int32_t>(1, s.height / std::max<int32_t>(1, s.renderScale));
}

// What field and colour-map indices refer to; the same on every rank.
struct ViewChoices {
  std::vector<std::string> fields;
  std::vector<std::string> colormaps;  // the job's --colormap first, then the other built-ins
  bool cutAvailable = true;            // false when the job's --clip planes leave no room
};

}  // namespace sm::view
