// Stopping a read whose result is no longer wanted: the viewer reads the next time step ahead
// while a frame renders, and when the user closes the window or jumps to another step, that read
// should end at once rather than run to the end of a large file first.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>

namespace sm::io {

// Asked between pieces, files, sections and compressed blocks; true stops the read. It may be
// called from several reading threads at once, so it must be thread-safe (an atomic flag).
// Empty: the read is never stopped.
using StopRequested = std::function<bool()>;

// Not an sm::Error: nothing is wrong with the input. The caller asked for the stop and drops
// the read, so this never reaches a user as an error message.
class ReadStopped : public std::runtime_error {
 public:
  explicit ReadStopped(const std::string& source)
      : std::runtime_error(source + ": reading stopped on request") {}
};

inline void throwIfStopped(const StopRequested& stop, const std::string& source) {
  if (stop && stop()) throw ReadStopped(source);
}

}  // namespace sm::io
