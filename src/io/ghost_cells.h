// The cells a VTK ghost array (cell array "vtkGhostType", vtkDataSetAttributes::CellGhostTypes)
// takes out of a rendering, shared by the .vtu and legacy .vtk readers.
//
// DUPLICATECELL (1): another piece owns the cell; drawing both copies would count the volume
// twice. HIDDENCELL (32): the writer blanked the cell (ParaView does not draw it, and VTK's
// filters treat it as absent). The other flags (connectivity levels, refined, exterior) describe
// cells that are still drawn.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/log.h"

namespace sm::io {

class GhostCells {
 public:
  static constexpr int64_t kDuplicate = 1;
  static constexpr int64_t kHidden = 32;

  // True, and counted, when cell c is left out; `flags` is the ghost array (empty: none).
  bool skip(const std::vector<int64_t>& flags, uint64_t c) {
    if (flags.empty()) return false;
    if (flags[c] & kDuplicate) {
      ++duplicate_;
      return true;
    }
    if (flags[c] & kHidden) {
      ++hidden_;
      return true;
    }
    return false;
  }

  // One warning per kind that was skipped, naming the file.
  void warn(const std::string& source) const {
    if (duplicate_)
      log::warning(source, ": skipped ", duplicate_,
                   " ghost cells (vtkGhostType DUPLICATECELL: owned by another piece)");
    if (hidden_)
      log::warning(source, ": skipped ", hidden_, " hidden cells (vtkGhostType HIDDENCELL)");
  }

 private:
  uint64_t duplicate_ = 0, hidden_ = 0;
};

}  // namespace sm::io
