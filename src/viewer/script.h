// --script FILE: input replayed frame by frame, so that tests (and demos) drive the viewer
// deterministically through the same input handling as the window. The format (one command per
// line) is scriptHelp(), printed by `shellmarch view --help-script`.
#pragma once

#include <deque>
#include <istream>
#include <string>
#include <vector>

#include "viewer/input.h"

namespace sm::view {

std::string scriptHelp();

class Script {
 public:
  Script() = default;
  // The whole text, parsed up front; errors name `name` and the line.
  static Script parse(const std::string& text, const std::string& name);
  // A file, parsed up front; "-" streams standard input instead, read only as far as the next
  // frame needs, so that another program can drive the viewer through a pipe.
  static Script load(const std::string& path);

  // Events for the next frame; false once the script is over.
  bool nextFrame(std::vector<InputEvent>& events);

 private:
  friend struct ScriptParser;
  void feed(const std::string& line);
  void endOfInput();

  std::deque<std::vector<InputEvent>> frames_;
  std::vector<InputEvent> pending_;  // input for the frame after the last complete one
  double cursorX_ = 0, cursorY_ = 0;
  std::string name_;
  int lineNumber_ = 0;
  std::istream* stream_ = nullptr;  // standard input while streaming
};

}  // namespace sm::view
