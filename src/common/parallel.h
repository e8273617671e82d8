// Minimal data parallelism for CPU stages (reference renderer, readers). Preparation benchmarks
// are stated per core, so prep code calls these with threads = 1 unless told otherwise.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace sm {

// Logical cores of the machine (std::thread::hardware_concurrency), whatever this process may use.
unsigned machineThreads();

// hardwareThreads() and what decided it (--stats-json reports both).
struct ThreadBudget {
  unsigned threads = 1;
  std::string reason;  // "OMP_NUM_THREADS", "affinity mask", "cores / 4 ranks on this node"
};
// The threads this process should use, as HPC tools count them: OMP_NUM_THREADS when set (its
// first entry, a positive integer), else the CPUs in this process's affinity mask (what mpirun's
// binding or taskset leaves it), but no more than the node's share of each rank of this job on
// this node (unbound, or bound to a socket, every rank would otherwise start one thread per core
// it may use and oversubscribe the node). Tests pass their own `env` (default std::getenv),
// `maskCpus` (default sched_getaffinity's count) and `nodeCpus` (default machineThreads()).
ThreadBudget threadBudget(const std::function<const char*(const char*)>& env = {},
                          unsigned maskCpus = 0, unsigned nodeCpus = 0);
unsigned hardwareThreads();  // threadBudget().threads, computed once

// Calls body(begin, end) on disjoint chunks of [0, n) from up to `threads` threads (0 = all).
// Exceptions from any chunk are rethrown (the first one) after all threads finish.
void parallelFor(int64_t n, const std::function<void(int64_t, int64_t)>& body, unsigned threads = 0,
                 int64_t minChunk = 1024);

}  // namespace sm
