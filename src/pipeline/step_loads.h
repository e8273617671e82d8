// Loads the scalars of the steps frames show, now or ahead of the frame, through a
// render::ScalarPrefetcher: `render --time all` prefetches the next step of its sequence, and
// `view` the next step while it plays. A collective source (streamed cell data) reads its next
// step's cells ahead on a thread of its own; averaging them onto the points takes every rank, so
// it runs when the frame starts.
#pragma once

#include <atomic>
#include <cstdint>
#include <future>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pipeline/step_source.h"
#include "render/scalar_prefetch.h"

namespace sm::app {

class StepLoads {
 public:
  // All three must outlive the loads.
  StepLoads(const StepSource& source, const prep::PreparedRank& rank, render::GpuScene& gpu)
      : source_(source), rank_(rank), prefetcher_(gpu) {}
  // A read still running ahead is stopped, not waited for to the end (closing the viewer).
  ~StepLoads() { discard(); }
  StepLoads(const StepLoads&) = delete;
  StepLoads& operator=(const StepLoads&) = delete;

  // Before a frame of `field`'s `step`: from the prefetch when it loaded that step, otherwise now
  // (a prefetch of another step is stopped and dropped first). Collective for a collective
  // source.
  render::ScalarSwitch loadFor(const std::string& field, uint64_t step);
  // While a frame renders, the next one's step (one thread, leaving the cores to the frame). A
  // prefetch of that step already under way is kept; one of another step is dropped.
  void prefetch(const std::string& field, uint64_t step);
  // Stops a prefetch under way (its read ends at the next piece, file, section or compressed
  // block: io::ReadOptions::stopRequested), waits for it and drops it, errors included: its step
  // is not shown.
  void discard();
  // Reads ahead that discard() stopped before they ended.
  uint64_t stoppedReads() const { return stoppedReads_; }

 private:
  struct CellsRead {
    std::vector<float> values;
    double ms;
  };
  render::ScalarPrefetcher::Load load(const std::string& field, uint64_t step, bool ahead);
  // Runs a read ahead, counting it when discard() stopped it.
  template <class Read>
  auto countingStops(Read&& read) {
    try {
      return read();
    } catch (const io::ReadStopped&) {
      ++stoppedReads_;
      throw;
    }
  }
  render::ScalarSwitch takeCells();
  io::StopRequested stopRequested() const;

  const StepSource& source_;
  const prep::PreparedRank& rank_;
  render::ScalarPrefetcher prefetcher_;
  std::future<CellsRead> cellsAhead_;
  std::optional<std::pair<std::string, uint64_t>> ahead_;  // the step a prefetch is loading
  // Set while discard() stops the read ahead; reading threads poll it (hence atomic).
  std::atomic<bool> stop_{false};
  std::atomic<uint64_t> stoppedReads_{0};
};

}  // namespace sm::app
