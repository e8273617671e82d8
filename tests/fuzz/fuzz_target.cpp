// libFuzzer entry point, compiled once per target with SHELLMARCH_FUZZ_TARGET naming a
// sm::fuzz::Target (tests/fuzz/CMakeLists.txt). The work is in fuzz_inputs.cpp, which the
// regression test shares.
#include <cstdio>
#include <cstdlib>

#include "fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    sm::fuzz::runInput(sm::fuzz::Target::SHELLMARCH_FUZZ_TARGET, {data, size});
  } catch (const sm::fuzz::FuzzBug& e) {
    // A finding like a crash: libFuzzer saves the input as crash-<sha1>.
    std::fprintf(stderr, "fuzz bug: %s\n", e.what());
    std::abort();
  }
  return 0;
}
