#include "io_core/read_options.h"

#include <algorithm>

#include "common/error.h"

namespace sm::io {

std::vector<int> choosePieces(const std::string& path, size_t count, const ReadOptions& options) {
  std::vector<int> chosen = options.pieces;
  if (chosen.empty()) {
    for (size_t i = 0; i < count; ++i) chosen.push_back(static_cast<int>(i));
    return chosen;
  }
  std::sort(chosen.begin(), chosen.end());
  for (size_t i = 0; i < chosen.size(); ++i) {
    if (chosen[i] < 0 || static_cast<size_t>(chosen[i]) >= count)
      throw FileError(path, "has no piece ", chosen[i], " (pieces 0 to ",
                      static_cast<int64_t>(count) - 1, ")");
    if (i > 0 && chosen[i] == chosen[i - 1])
      throw FileError(path, "piece ", chosen[i], " asked for twice");
  }
  return chosen;
}

}  // namespace sm::io
