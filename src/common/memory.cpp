#include "common/memory.h"

#include <cstdio>
#include <cstring>

namespace sm {
namespace {
uint64_t statusField(const char* key) {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256];
  uint64_t value = 0;
  size_t klen = std::strlen(key);
  while (std::fgets(line, sizeof line, f)) {
    if (std::strncmp(line, key, klen) == 0) {
      unsigned long long kb = 0;
      std::sscanf(line + klen, " %llu", &kb);
      value = kb * 1024ull;
      break;
    }
  }
  std::fclose(f);
  return value;
}
}  // namespace

uint64_t peakResidentBytes() {
  return statusField("VmHWM:");
}
uint64_t currentResidentBytes() {
  return statusField("VmRSS:");
}
bool resetPeakResident() {
  std::FILE* f = std::fopen("/proc/self/clear_refs", "w");
  if (!f) return false;
  bool ok = std::fputs("5", f) >= 0;
  return (std::fclose(f) == 0) && ok;
}
}  // namespace sm
