#pragma once

#include <cstdint>

namespace sm {
// Peak resident set size of this process so far (VmHWM), in bytes; 0 where unknown.
uint64_t peakResidentBytes();
// Current resident set size (VmRSS), in bytes; 0 where unknown.
uint64_t currentResidentBytes();
// Resets the peak counter (Linux: writes 5 to /proc/self/clear_refs); returns false if unsupported.
bool resetPeakResident();
}  // namespace sm
