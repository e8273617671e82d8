// Input events, from the window or from a script, and what they do to the viewer's state. The
// window and the script both produce InputEvents, so a script exercises the same handling as a
// user at the window.
#pragma once

#include <string>
#include <vector>

#include "viewer/camera_controller.h"
#include "viewer/view_state.h"

namespace sm::view {

enum class Key {
  None,
  NextStep,          // right arrow
  PrevStep,          // left arrow
  TogglePlay,        // space
  MoreOpaque,        // up arrow
  LessOpaque,        // down arrow
  NextField,         // f (shift: previous)
  NextColormap,      // c (shift: previous)
  FinerStep,         // [
  CoarserStep,       // ]
  ResetView,         // r
  Screenshot,        // s
  ToggleOverlay,     // o
  ToggleLegend,      // l
  ToggleCut,         // x (shift: keep the other side)
  CutNearer,         // ,
  CutFarther,        // .
  ToggleLogScale,    // g
  ToggleProjection,  // p
  Help,              // h
  Quit,              // q, escape
};

enum class Button { Left, Middle, Right };

struct InputEvent {
  enum class Type { Move, Press, Release, Scroll, KeyPress, Screenshot, Resize, Quit } type;
  double x = 0, y = 0;  // Move: cursor in window pixels; Scroll: y = clicks; Resize: size
  Button button = Button::Left;
  Key key = Key::None;
  bool shift = false;
  std::string path;  // Screenshot: where to write this frame
};

// Key names as scripts and the controls table spell them ("right", "f", "[", ...).
Key keyFromName(const std::string& name);
// Whether a key held down acts again with each of the window's auto-repeats: stepping keys do;
// toggles (play, overlay), screenshots, help and quit act once per press.
bool keyRepeats(Key key);
std::string controlsHelp();

// Requests that are not part of the broadcast state: they concern rank 0 only.
struct LocalRequests {
  std::vector<std::string> screenshots;  // "" = the next numbered name
  bool toggleOverlay = false;
  bool toggleLegend = false;
  bool help = false;
  int resizeWidth = 0, resizeHeight = 0;  // > 0: ask the window for this size
};

// Applies events to the state. Drags are tracked across calls (a button held over several
// frames keeps dragging).
class InputHandler {
 public:
  InputHandler(const scene::Camera& home, const ViewChoices& choices);
  CameraController& controller() { return controller_; }

  void apply(const InputEvent& e, ViewState& state, LocalRequests& local);

  static constexpr double kOpacityFactor = 1.25;
  static constexpr double kStepFactor = 1.25;
  // The cut moves by this fraction of the home camera's distance to the data's centre per press.
  static constexpr double kCutStepFraction = 0.02;

 private:
  void onMove(double x, double y, ViewState& state);
  void onKey(const InputEvent& e, ViewState& state, LocalRequests& local);
  void onCutKey(const InputEvent& e, ViewState& state) const;
  enum class Drag { None, Orbit, Pan, Zoom };
  CameraController controller_;
  double cutStep_;       // world distance per cut key press
  ViewChoices choices_;  // a copy: only its sizes and cutAvailable matter here
  Drag drag_ = Drag::None;
  Button dragButton_ = Button::Left;
  double cursorX_ = 0, cursorY_ = 0;
};

}  // namespace sm::view
