#include "common/parallel.h"

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace sm {

unsigned machineThreads() {
  return std::max(1u, std::thread::hardware_concurrency());
}

namespace {

// A positive count at the start of `text` ("4", or OpenMP's nested list "4,2"), else 0.
unsigned leadingCount(const char* text) {
  if (!text) return 0;
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text, &end, 10);
  if (end == text || errno || v <= 0 || (*end && *end != ',')) return 0;
  return static_cast<unsigned>(std::min<long>(v, 1 << 16));
}

unsigned affinityCpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) return machineThreads();
  return std::max(1, CPU_COUNT(&set));
}

}  // namespace

ThreadBudget threadBudget(const std::function<const char*(const char*)>& env, unsigned maskCpus,
                          unsigned nodeCpus) {
  auto get = [&](const char* name) { return env ? env(name) : std::getenv(name); };
  if (const unsigned omp = leadingCount(get("OMP_NUM_THREADS"))) return {omp, "OMP_NUM_THREADS"};
  const unsigned mask = maskCpus ? maskCpus : affinityCpus();
  const unsigned node = nodeCpus ? nodeCpus : machineThreads();
  // Ranks of this job on this node (Open MPI, MPICH/Hydra, Slurm), when the launcher bound none.
  unsigned local = 0;
  for (const char* var : {"OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS", "SLURM_NTASKS_PER_NODE"})
    if ((local = leadingCount(get(var)))) break;
  // min(): a mask of one socket shared by that socket's ranks must not give each the socket.
  if (local > 1 && mask * local > node)
    return {std::max(1u, std::min(mask, node / local)),
            "cores / " + std::to_string(local) + " ranks on this node"};
  return {mask, "affinity mask"};
}

unsigned hardwareThreads() {
  static const unsigned threads = threadBudget().threads;
  return threads;
}

void parallelFor(int64_t n, const std::function<void(int64_t, int64_t)>& body, unsigned threads,
                 int64_t minChunk) {
  if (n <= 0) return;
  if (threads == 0) threads = hardwareThreads();
  int64_t chunks = std::min<int64_t>(threads * 8, (n + minChunk - 1) / minChunk);
  if (threads == 1 || chunks <= 1) {
    body(0, n);
    return;
  }
  std::atomic<int64_t> next{0};
  std::exception_ptr error;
  std::mutex errorMutex;
  auto worker = [&] {
    for (;;) {
      int64_t c = next++;
      if (c >= chunks) return;
      int64_t b = n * c / chunks, e = n * (c + 1) / chunks;
      try {
        body(b, e);
      } catch (...) {
        std::lock_guard lock(errorMutex);
        if (!error) error = std::current_exception();
        next = chunks;
      }
    }
  };
  unsigned nt = static_cast<unsigned>(std::min<int64_t>(threads, chunks));
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < nt; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace sm
