#include "common/progress.h"

#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace sm {
namespace {

std::atomic<bool> gAllowed{false};
// Work inside work (the pieces of each step's .pvtu): only the outermost counts on the line.
std::atomic<int> gActive{0};

// SHELLMARCH_PROGRESS: "1" forces lines on, "0" off, anything else (or unset) leaves it to
// allowProgress and the terminal.
int forced() {
  const char* v = std::getenv("SHELLMARCH_PROGRESS");
  if (!v) return -1;
  if (std::strcmp(v, "1") == 0) return 1;
  if (std::strcmp(v, "0") == 0) return 0;
  return -1;
}

}  // namespace

void allowProgress(bool allowed) {
  gAllowed = allowed;
}

std::string shortDuration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buf[32];
  if (s < 60)
    std::snprintf(buf, sizeof buf, "%ld s", s);
  else if (s < 3600)
    std::snprintf(buf, sizeof buf, "%ld min %02ld s", s / 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%ld h %02ld min", s / 3600, (s / 60) % 60);
  return buf;
}

Progress::Progress(std::string what, uint64_t total) : what_(std::move(what)), total_(total) {
  if (gActive++ > 0) return;
  const int f = forced();
  if (f == 1)
    mode_ = Mode::Lines;
  else if (f == -1 && gAllowed && isatty(STDERR_FILENO))
    mode_ = Mode::Terminal;
}

Progress::~Progress() {
  --gActive;
  // Ended early (an error): the error's line replaces the progress line.
  if (mode_ != Mode::Terminal || !printedAny_ || endedLine_) return;
  std::fputs("\r\033[K", stderr);
  std::fflush(stderr);
}

void Progress::advance(uint64_t by) {
  done_ += by;
  if (mode_ == Mode::Off) return;
  const double now = timer_.seconds();
  const bool last = total_ && done_ >= total_;
  // A short job ends before the first line would help anyone: nothing within the first second.
  if (now < 1.0 && !(mode_ == Mode::Lines && last)) return;
  if (!last && lastPrint_ >= 0 && now - lastPrint_ < 0.2) return;
  lastPrint_ = now;
  print(last);
}

void Progress::print(bool last) {
  const double elapsed = timer_.seconds();
  std::string line = "shellmarch: " + what_ + " " + std::to_string(done_);
  if (total_) {
    line += "/" + std::to_string(total_) + " (" +
            std::to_string(int(std::floor(100.0 * double(done_) / double(total_)))) + "%)";
  }
  line += ", " + shortDuration(elapsed);
  if (total_ && done_ && !last)
    line += ", about " + shortDuration(elapsed * double(total_ - done_) / double(done_)) + " left";
  if (mode_ == Mode::Terminal) {
    // The last state stays on screen, on its own line, above what the command prints next.
    std::fprintf(stderr, "\r\033[K%s%s", line.c_str(), last ? "\n" : "");
    endedLine_ = last;
  } else
    std::fprintf(stderr, "%s\n", line.c_str());
  std::fflush(stderr);
  printedAny_ = true;
}

}  // namespace sm
