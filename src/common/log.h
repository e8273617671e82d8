// Diagnostics on stderr. Warnings are for input the tools accept but change (skipped cells, fixed
// orientation); they never replace an error for input that cannot be used.
#pragma once

#include <string>

#include "common/error.h"

namespace sm::log {

enum class Level { Quiet = 0, Warning = 1, Info = 2, Debug = 3 };

void setLevel(Level level);
Level level();
// Prefix added to every line (the MPI rank in parallel runs, e.g. "[rank 2] ").
void setPrefix(const std::string& prefix);

void warningLine(const std::string& line);
// True the first time `key` is passed in this process: for warnings said once per run, however
// often the input that causes them is read (pieces, steps, frames).
bool firstTime(const std::string& key);
void infoLine(const std::string& line);
void debugLine(const std::string& line);

template <typename... Args>
void warning(Args&&... args) {
  if (level() >= Level::Warning) warningLine(concat(std::forward<Args>(args)...));
}
template <typename... Args>
void info(Args&&... args) {
  if (level() >= Level::Info) infoLine(concat(std::forward<Args>(args)...));
}
template <typename... Args>
void debug(Args&&... args) {
  if (level() >= Level::Debug) debugLine(concat(std::forward<Args>(args)...));
}

}  // namespace sm::log
