#include "pipeline/step_loads.h"

#include "common/fault_injection.h"
#include "common/timer.h"

namespace sm::app {

render::ScalarSwitch StepLoads::loadFor(const std::string& field, uint64_t step) {
  if (ahead_ && *ahead_ != std::pair(field, step)) discard();
  ahead_.reset();
  if (prefetcher_.pending()) return prefetcher_.swap();
  if (cellsAhead_.valid()) return takeCells();
  return prefetcher_.loadNow(load(field, step, false));
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
  if (!source_.collective(field)) {
    prefetcher_.prefetch(load(field, step, true));
    return;
  }
  cellsAhead_ = std::async(std::launch::async, [this, field, step] {
    return countingStops([&] {
      const io::StopRequested stop = stopRequested();
      fault::atReadAhead(stop);
      Timer t;
      CellsRead r{source_.readCells(field, step, 1, stop), 0.0};
      r.ms = t.ms();
      return r;
    });
  });
}

void StepLoads::discard() {
  ahead_.reset();
  stop_ = true;
  prefetcher_.discard();
  if (cellsAhead_.valid()) {
    cellsAhead_.wait();
    cellsAhead_ = {};  // a stored error (io::ReadStopped, most likely) goes with it
  }
  stop_ = false;
}

io::StopRequested StepLoads::stopRequested() const {
  return [&stop = stop_] { return stop.load(std::memory_order_relaxed); };
}

// Ahead: on one thread (leaving the cores to the frame), stoppable; now: on every core.
render::ScalarPrefetcher::Load StepLoads::load(const std::string& field, uint64_t step,
                                               bool ahead) {
  if (!ahead) return [this, field, step] { return source_.scalars(rank_, field, step); };
  return [this, field, step] {
    return countingStops([&] {
      const io::StopRequested stop = stopRequested();
      fault::atReadAhead(stop);
      return source_.scalars(rank_, field, step, 1, stop);
    });
  };
}

}  // namespace sm::app
