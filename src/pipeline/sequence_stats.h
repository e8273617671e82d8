// Statistics of a step sequence (`render --time all [--repeat R]`): per-frame time including the
// switch of scalars, frames per second per run (mean and spread over runs, as the paper reports
// time-varying data), and how long frames waited for their scalars, i.e. whether prefetching hid
// the reading and upload of the next step.
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "comm/reductions.h"
#include "render/gpu_scene.h"
#include "render/scalar_prefetch.h"

namespace sm::app {

class SequenceStats {
 public:
  SequenceStats(int runs, bool prefetch) : runs_(runs), prefetch_(prefetch) {}
  // This rank's times for one frame (no communication: frames stay undisturbed).
  void addFrame(int run, uint64_t step, double frameMs, double renderMs,
                const render::ScalarSwitch& scalars);
  // Collective: per-frame times are the slowest rank's; fps per run from their sum.
  nlohmann::json summary(const render::GpuScene& gpu, comm::Communicator& comm) const;

 private:
  struct Frame {
    int run;
    uint64_t step;
    double frameMs, renderMs;
    render::ScalarSwitch scalars;
  };
  int runs_;
  bool prefetch_;
  std::vector<Frame> frames_;
};

// The summary in a few lines (rank 0 prints it under --stats).
void printSequenceSummary(const nlohmann::json& summary);

}  // namespace sm::app
