#include "viewer/script.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include "common/error.h"
#include "common/file_util.h"

namespace sm::view {
namespace {

// One line's words, with its place for error messages.
struct Line {
  std::vector<std::string> words;
  std::string where;
  [[noreturn]] void fail(const std::string& why) const {
    throw Error("--script ", where, ": ", why);
  }
  double number(size_t i) const {
    if (i >= words.size()) fail("'" + words[0] + "' needs more arguments");
    char* end = nullptr;
    double v = std::strtod(words[i].c_str(), &end);
    if (*end || !std::isfinite(v)) fail("'" + words[i] + "' is not a number");
    return v;
  }
  Button button(size_t i) const {
    if (i < words.size()) {
      if (words[i] == "left") return Button::Left;
      if (words[i] == "middle") return Button::Middle;
      if (words[i] == "right") return Button::Right;
    }
    fail("'" + words[0] + "' needs a button: left, middle or right");
  }
  bool shiftAt(size_t i) const {
    if (i >= words.size()) return false;
    if (words[i] == "shift" && i + 1 == words.size()) return true;
    fail("unexpected '" + words[i] + "' (only 'shift' may follow)");
  }
  void expectWords(size_t n) const {
    if (words.size() != n)
      fail("'" + words[0] + "' takes " + std::to_string(n - 1) + " argument(s)");
  }
};

}  // namespace

// Parsing, with access to the script's state (cursor, pending input) across lines.
struct ScriptParser {
  static void add(Script& s, InputEvent e) { s.pending_.push_back(std::move(e)); }
  static void frame(Script& s, long n) {
    for (long i = 0; i < n; ++i) {
      s.frames_.push_back(std::move(s.pending_));
      s.pending_.clear();
    }
  }
  static void drag(const Line& l, Script& b) {
    if (l.words.size() < 4) l.fail("'drag' needs: BUTTON DX DY [N] [shift]");
    const Button button = l.button(1);
    const double dx = l.number(2), dy = l.number(3);
    size_t next = 4;
    long n = 1;
    if (l.words.size() > 4 && l.words[4] != "shift") {
      n = long(l.number(4));
      if (n < 1 || n > 100000 || double(n) != l.number(4)) l.fail("'drag' needs a whole N >= 1");
      next = 5;
    }
    const bool shift = l.shiftAt(next);
    // Where the drag starts, restated: the window's own cursor events may have moved it since.
    add(b, {InputEvent::Type::Move, b.cursorX_, b.cursorY_, button, Key::None, shift, {}});
    add(b, {InputEvent::Type::Press, 0, 0, button, Key::None, shift, {}});
    const double x0 = b.cursorX_, y0 = b.cursorY_;
    for (long i = 1; i <= n; ++i) {
      b.cursorX_ = x0 + dx * double(i) / double(n);
      b.cursorY_ = y0 + dy * double(i) / double(n);
      add(b, {InputEvent::Type::Move, b.cursorX_, b.cursorY_, button, Key::None, shift, {}});
    }
    add(b, {InputEvent::Type::Release, 0, 0, button, Key::None, shift, {}});
  }

  static void command(const Line& l, Script& b) {
    const std::string& c = l.words[0];
    using T = InputEvent::Type;
    if (c == "move") {
      l.expectWords(3);
      b.cursorX_ = l.number(1);
      b.cursorY_ = l.number(2);
      add(b, {T::Move, b.cursorX_, b.cursorY_, Button::Left, Key::None, false, {}});
    } else if (c == "press" || c == "release") {
      add(b,
          {c == "press" ? T::Press : T::Release, 0, 0, l.button(1), Key::None, l.shiftAt(2), {}});
    } else if (c == "drag") {
      drag(l, b);
    } else if (c == "scroll") {
      l.expectWords(2);
      add(b, {T::Scroll, 0, l.number(1), Button::Left, Key::None, false, {}});
    } else if (c == "key") {
      if (l.words.size() < 2) l.fail("'key' needs a key name");
      Key k = keyFromName(l.words[1]);
      if (k == Key::None) l.fail("unknown key '" + l.words[1] + "'");
      add(b, {T::KeyPress, 0, 0, Button::Left, k, l.shiftAt(2), {}});
    } else if (c == "screenshot") {
      l.expectWords(2);
      add(b, {T::Screenshot, 0, 0, Button::Left, Key::None, false, l.words[1]});
    } else if (c == "resize") {
      l.expectWords(3);
      const double w = l.number(1), h = l.number(2);
      if (w < 1 || h < 1 || w > 16384 || h > 16384 || w != std::floor(w) || h != std::floor(h))
        l.fail("'resize' needs a size from 1x1 to 16384x16384");
      add(b, {T::Resize, w, h, Button::Left, Key::None, false, {}});
    } else if (c == "frame") {
      const double n = l.words.size() > 1 ? l.number(1) : 1;
      if (l.words.size() > 2 || n < 1 || n > 1e7 || n != std::floor(n))
        l.fail("'frame' takes a whole N >= 1");
      frame(b, long(n));
    } else if (c == "quit") {
      l.expectWords(1);
      add(b, {T::Quit, 0, 0, Button::Left, Key::None, false, {}});
    } else {
      l.fail("unknown command '" + c + "'");
    }
  }
};

std::string scriptHelp() {
  return "shellmarch view --script FILE (or - for standard input, read as frames need it):\n"
         "one command per line, '#' starts a comment.\n"
         "Input commands go to the next frame rendered; window pixels, y down.\n"
         "  move X Y                       cursor to (X, Y); drags while a button is held\n"
         "  press left|middle|right [shift]\n"
         "  release left|middle|right\n"
         "  drag left|middle|right DX DY [N] [shift]\n"
         "                                 press at the cursor, move by (DX, DY) in N equal\n"
         "                                 moves (default 1), release\n"
         "  scroll CLICKS                  mouse wheel; positive zooms in\n"
         "  key NAME [shift]               right left space up down f c [ ] r s o l x , . g p h q "
         "escape\n"
         "  screenshot FILE                write this frame (no overlay) to FILE\n"
         "  resize W H                     ask for a W x H window (headless: the image size)\n"
         "  frame [N]                      render N frames (default 1); the input above goes\n"
         "                                 to the first of them\n"
         "  quit                           end after the input above\n"
         "Input after the last 'frame' goes to one more frame. After the script, the window's\n"
         "own input continues (headless, or with --frames, the viewer stops).\n";
}

void Script::feed(const std::string& text) {
  std::string raw = text;
  ++lineNumber_;
  if (auto hash = raw.find('#'); hash != std::string::npos) raw.resize(hash);
  Line l{{}, name_ + ":" + std::to_string(lineNumber_)};
  std::istringstream words(raw);
  for (std::string w; words >> w;) l.words.push_back(w);
  if (!l.words.empty()) ScriptParser::command(l, *this);
}

void Script::endOfInput() {
  if (!pending_.empty()) ScriptParser::frame(*this, 1);
  stream_ = nullptr;
}

Script Script::parse(const std::string& text, const std::string& name) {
  Script s;
  s.name_ = name;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) s.feed(line);
  s.endOfInput();
  return s;
}

Script Script::load(const std::string& path) {
  if (path != "-") return parse(readTextFile(path), path);
  Script s;
  s.name_ = "<stdin>";
  s.stream_ = &std::cin;
  return s;
}

bool Script::nextFrame(std::vector<InputEvent>& events) {
  std::string line;
  while (frames_.empty() && stream_) {
    if (std::getline(*stream_, line))
      feed(line);
    else
      endOfInput();
  }
  if (frames_.empty()) return false;
  for (auto& e : frames_.front()) events.push_back(std::move(e));
  frames_.pop_front();
  return true;
}

}  // namespace sm::view
