// Minimal data parallelism for CPU stages (reference renderer, readers). Preparation benchmarks
// are stated per core, so prep code calls these with threads = 1 unless told otherwise.
#pragma once

#include <cstdint>
#include <functional>

namespace sm {

unsigned hardwareThreads();
// Calls body(begin, end) on disjoint chunks of [0, n) from up to `threads` threads (0 = all).
// Exceptions from any chunk are rethrown (the first one) after all threads finish.
void parallelFor(int64_t n, const std::function<void(int64_t, int64_t)>& body, unsigned threads = 0,
                 int64_t minChunk = 1024);

}  // namespace sm
