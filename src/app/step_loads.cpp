#include "app/step_loads.h"

#include "common/timer.h"

namespace sm::app {

render::ScalarSwitch StepLoads::loadFor(const std::string& field, uint64_t step) {
  if (ahead_ && *ahead_ != std::pair(field, step)) discard();
  ahead_.reset();
  if (prefetcher_.pending()) return prefetcher_.swap();
  if (cellsAhead_.valid()) return takeCells();
  return prefetcher_.loadNow(load(field, step, 0));
}

render::ScalarSwitch StepLoads::takeCells() {
  Timer wait;
  CellsRead ahead = cellsAhead_.get();
  const double waitMs = wait.ms();
  render::ScalarSwitch s =
      prefetcher_.loadNow([&] { return source_.scalarsFromCells(rank_, ahead.values); });
  // The read ran during the frame before; the averaging, gather and upload did not.
  s.waitMs += waitMs;
  s.loadMs += ahead.ms;
  s.prefetched = true;
  return s;
}

void StepLoads::prefetch(const std::string& field, uint64_t step) {
  if (ahead_ && *ahead_ == std::pair(field, step)) return;
  discard();
  ahead_.emplace(field, step);
  if (!source_.collective()) {
    prefetcher_.prefetch(load(field, step, 1));
    return;
  }
  cellsAhead_ = std::async(std::launch::async, [&source = source_, field, step] {
    Timer t;
    CellsRead r{source.readCells(field, step, 1), 0.0};
    r.ms = t.ms();
    return r;
  });
}

void StepLoads::discard() {
  ahead_.reset();
  prefetcher_.discard();
  if (cellsAhead_.valid()) {
    cellsAhead_.wait();
    cellsAhead_ = {};  // a stored error goes with it
  }
}

render::ScalarPrefetcher::Load StepLoads::load(const std::string& field, uint64_t step,
                                               unsigned threads) const {
  return [&source = source_, &rank = rank_, field, step, threads] {
    return source.scalars(rank, field, step, threads);
  };
}

}  // namespace sm::app
