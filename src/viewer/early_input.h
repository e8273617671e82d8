// Input that arrives while a frame is still being made. A new field's range pass reads every step
// of the field before the frame can render; meanwhile the window's events are taken here, looked
// at for a close or quit, or a press of the field key, so that the pass can stop at once, and
// handed to the next frame in order. A script's input stays with its frames (a script's "frame"
// renders the input above it whatever follows); SHELLMARCH_FAULT=at=range-pass,action=close stands
// for a close then, and action=next-field for a press of the field key.
#pragma once

#include <vector>

#include "viewer/input.h"
#include "viewer/script.h"
#include "viewer/view_state.h"
#include "viewer/window.h"

namespace sm::view {

class EarlyInput {
 public:
  EarlyInput(Window& window, Script& script) : window_(window), script_(script) {}

  // What has arrived that ends a range pass: a close or quit (the viewer ends), else a press of
  // the field key (the next frame shows another field; the pass's field is not waited for).
  PassInterrupt interruptArrived();
  // The next frame's input: what arrived early, then the window's, then the script's. Returns
  // Script::nextFrame's answer (false once the script is over).
  bool takeFrame(std::vector<InputEvent>& events);

 private:
  Window& window_;
  Script& script_;
  std::vector<InputEvent> early_;
  bool quit_ = false, fieldChange_ = false;
};

}  // namespace sm::view
