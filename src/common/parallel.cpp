#include "common/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace sm {

unsigned hardwareThreads() {
  return std::max(1u, std::thread::hardware_concurrency());
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
