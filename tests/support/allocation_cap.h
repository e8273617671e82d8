// A cap on any single allocation, for tests of readers that must not allocate what a file merely
// claims. Linking allocation_cap.cpp into a test replaces the global operator new (plain and
// aligned); while an AllocationCap is alive, a larger request throws std::bad_alloc, which such
// tests count as a failure. Readers are quiet for its scope too.
#pragma once

#include <cstddef>

#include "common/log.h"

namespace sm::test {

class AllocationCap {
 public:
  explicit AllocationCap(std::size_t bytes = std::size_t(32) << 20);
  ~AllocationCap();
  AllocationCap(const AllocationCap&) = delete;
  AllocationCap& operator=(const AllocationCap&) = delete;

 private:
  log::Level level_;
};

}  // namespace sm::test
