#include "viewer/input.h"

#include <map>

#include <glm/geometric.hpp>

namespace sm::view {
namespace {

int cycle(int value, int delta, size_t count) {
  if (count == 0) return 0;
  const int n = int(count);
  return ((value + delta) % n + n) % n;
}

}  // namespace

Key keyFromName(const std::string& name) {
  static const std::map<std::string, Key> keys = {
      {"right", Key::NextStep},   {"space", Key::TogglePlay},
      {"left", Key::PrevStep},    {"up", Key::MoreOpaque},
      {"down", Key::LessOpaque},  {"f", Key::NextField},
      {"c", Key::NextColormap},   {"[", Key::FinerStep},
      {"]", Key::CoarserStep},    {"r", Key::ResetView},
      {"s", Key::Screenshot},     {"o", Key::ToggleOverlay},
      {"l", Key::ToggleLegend},   {"h", Key::Help},
      {"q", Key::Quit},           {"x", Key::ToggleCut},
      {",", Key::CutNearer},      {".", Key::CutFarther},
      {"g", Key::ToggleLogScale}, {"p", Key::ToggleProjection},
      {"escape", Key::Quit}};
  auto it = keys.find(name);
  return it == keys.end() ? Key::None : it->second;
}

bool keyRepeats(Key key) {
  switch (key) {
    case Key::NextStep:
    case Key::PrevStep:
    case Key::MoreOpaque:
    case Key::LessOpaque:
    case Key::NextField:
    case Key::NextColormap:
    case Key::FinerStep:
    case Key::CoarserStep:
    case Key::CutNearer:
    case Key::CutFarther:
      return true;
    default:
      return false;
  }
}

std::string controlsHelp() {
  return "shellmarch view controls:\n"
         "  left drag                     orbit about the point looked at\n"
         "  middle drag, shift+left drag  pan\n"
         "  wheel, right drag             zoom\n"
         "  right / left                  next / previous time step\n"
         "  space                         play / pause: a step a frame, the next read ahead\n"
         "  f / shift+f                   next / previous field\n"
         "  c / shift+c                   next / previous colour map\n"
         "  up / down                     opacity scale times / divided by 1.25\n"
         "  [ / ]                         finer / coarser sampling step (by 1.25)\n"
         "  r                             reset the view\n"
         "  s                             screenshot (PNG, without the overlay)\n"
         "  o                             overlay on / off\n"
         "  l                             colour legend on / off (in screenshots too)\n"
         "  x / shift+x                   cut away the near / far half: a clip plane through the\n"
         "                                point looked at, facing the camera; again: no cut\n"
         "  , / .                         move the cut nearer / farther\n"
         "  g                             log scale on / off (fields with a positive range)\n"
         "  p                             perspective / parallel projection (the wheel then\n"
         "                                changes the parallel scale)\n"
         "  h                             print these controls (on stderr)\n"
         "  q, escape                     quit\n";
}

InputHandler::InputHandler(const scene::Camera& home, const ViewChoices& choices)
    : controller_(home),
      cutStep_(kCutStepFraction * glm::length(home.eye - home.at)),
      choices_(choices) {}

void InputHandler::apply(const InputEvent& e, ViewState& state, LocalRequests& local) {
  controller_.setCamera(state.camera());
  switch (e.type) {
    case InputEvent::Type::Move:
      onMove(e.x, e.y, state);
      break;
    case InputEvent::Type::Press:
      if (drag_ != Drag::None) break;  // the first button held decides the drag
      dragButton_ = e.button;
      if (e.button == Button::Middle || (e.button == Button::Left && e.shift))
        drag_ = Drag::Pan;
      else
        drag_ = e.button == Button::Left ? Drag::Orbit : Drag::Zoom;
      break;
    case InputEvent::Type::Release:
      if (e.button == dragButton_) drag_ = Drag::None;
      break;
    case InputEvent::Type::Scroll:
      controller_.zoomWheel(e.y);
      break;
    case InputEvent::Type::KeyPress:
      onKey(e, state, local);
      break;
    case InputEvent::Type::Screenshot:
      local.screenshots.push_back(e.path);
      break;
    case InputEvent::Type::Resize:
      local.resizeWidth = int(e.x);
      local.resizeHeight = int(e.y);
      break;
    case InputEvent::Type::Quit:
      state.quit = 1;
      break;
  }
  state.setCamera(controller_.camera());
}

void InputHandler::onMove(double x, double y, ViewState& state) {
  const double dx = x - cursorX_, dy = y - cursorY_;
  cursorX_ = x;
  cursorY_ = y;
  switch (drag_) {
    case Drag::Orbit:
      controller_.orbitPixels(dx, dy, state.height);
      break;
    case Drag::Pan:
      controller_.panPixels(dx, dy, state.height);
      break;
    case Drag::Zoom:
      controller_.zoomPixels(dy, state.height);
      break;
    case Drag::None:
      break;
  }
}

void InputHandler::onKey(const InputEvent& e, ViewState& state, LocalRequests& local) {
  const int back = e.shift ? -1 : 1;
  switch (e.key) {
    case Key::NextStep:
      ++state.step;  // every rank wraps it into the field's steps
      break;
    case Key::PrevStep:
      --state.step;
      break;
    case Key::TogglePlay:
      state.playing = !state.playing;
      break;
    case Key::MoreOpaque:
      state.opacityScale *= kOpacityFactor;
      break;
    case Key::LessOpaque:
      state.opacityScale /= kOpacityFactor;
      break;
    case Key::NextField:
      state.field = cycle(state.field, back, choices_.fields.size());
      break;
    case Key::NextColormap:
      state.colormap = cycle(state.colormap, back, choices_.colormaps.size());
      break;
    case Key::FinerStep:
      state.dt /= kStepFactor;
      break;
    case Key::CoarserStep:
      state.dt *= kStepFactor;
      break;
    case Key::ResetView:
      controller_.reset();
      break;
    case Key::Screenshot:
      local.screenshots.push_back("");
      break;
    case Key::ToggleOverlay:
      local.toggleOverlay = true;
      break;
    case Key::ToggleLegend:
      local.toggleLegend = true;
      break;
    case Key::ToggleLogScale:
      state.logScale = !state.logScale;
      break;
    case Key::ToggleProjection:
      controller_.toggleProjection();
      break;
    case Key::Help:
      local.help = true;
      break;
    case Key::ToggleCut:
    case Key::CutNearer:
    case Key::CutFarther:
      onCutKey(e, state);
      break;
    case Key::Quit:
      state.quit = 1;
      break;
    case Key::None:
      break;
  }
}

// The cut is fixed in the world once made (orbit round it to see the cut face); made again, it
// faces the camera anew. The normal points away from the camera, so the half between the camera
// and the point looked at is cut away; shift keeps that half instead.
void InputHandler::onCutKey(const InputEvent& e, ViewState& state) const {
  if (!choices_.cutAvailable) return;
  if (e.key == Key::ToggleCut) {
    state.cut = !state.cut;
    if (state.cut) {
      state.cutPoint = state.at;
      state.cutNormal = glm::normalize(state.at - state.eye) * (e.shift ? -1.0 : 1.0);
    }
    return;
  }
  if (!state.cut) return;
  const double along =
      glm::dot(state.cutNormal, glm::normalize(state.at - state.eye)) >= 0 ? 1 : -1;
  // Farther from the camera whichever side the cut keeps.
  state.cutPoint += (e.key == Key::CutFarther ? 1.0 : -1.0) * along * cutStep_ * state.cutNormal;
}

}  // namespace sm::view
