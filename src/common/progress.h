// A progress line on standard error for long work (pieces written, frames rendered, steps read),
// for a person at a terminal: nothing when stderr is not a terminal (logs, CI, pipes), on ranks
// other than 0, or with --quiet. SHELLMARCH_PROGRESS=1 forces it on (one line per update, for
// tests and log files that want it), =0 off.
#pragma once

#include <cstdint>
#include <string>

#include "common/timer.h"

namespace sm {

// Whether progress lines may be shown in this process (the command line's entry point decides:
// rank 0, not --quiet); SHELLMARCH_PROGRESS overrides it either way.
void allowProgress(bool allowed);

class Progress {
 public:
  // `what` names the unit counted ("frame", "piece"); `total` 0 counts without an end. A Progress
  // made while another lives (in any thread) shows nothing: the outer work's line is the one.
  Progress(std::string what, uint64_t total);
  ~Progress();  // clears an unfinished line from the terminal
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void advance(uint64_t by = 1);  // shown at most 5 times a second, and at the end
  bool shown() const { return mode_ != Mode::Off; }

 private:
  enum class Mode { Off, Terminal, Lines };
  void print(bool last);
  std::string what_;
  uint64_t total_ = 0, done_ = 0;
  Mode mode_ = Mode::Off;
  Timer timer_;
  double lastPrint_ = -1;
  bool printedAny_ = false, endedLine_ = false;
};

// "12 s", "3 min 05 s", "1 h 02 min" for the line's elapsed and remaining time.
std::string shortDuration(double seconds);

}  // namespace sm
