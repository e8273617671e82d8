// Test bodies shared by in-process ranks (LocalCommunicator threads) and mpirun (MpiCommunicator):
// each runs on every rank of `comm`, calls the same collectives in the same order on every rank,
// and checks with non-fatal expectations only, so that a failure on one rank never leaves the
// others waiting in a collective. Images are checked on rank 0, statistics on every rank.
#pragma once

#include <memory>
#include <string>

#include "comm/communicator.h"
#include "compositor/host_lists.h"
#include "fragment_model.h"

namespace sm::comp::test {

// One rank's compositor and the writer that feeds it host lists through the device interface.
class RankRig {
 public:
  RankRig(comm::Communicator* comm, const vk::Context& ctx, int width, int height,
          const CompositorOptions& options);
  // Writes this rank's raw lists of `w` and composites (collective); the image on rank 0.
  std::vector<glm::vec4> run(const World& w, CompositeMethod method = CompositeMethod::Deep);
  DeepCompositor& compositor() { return *compositor_; }

 private:
  comm::Communicator* comm_;
  std::unique_ptr<DeepCompositor> compositor_;
  std::unique_ptr<ListWriter> writer_;
};

int rankOf(comm::Communicator* comm);
int ranksOf(comm::Communicator* comm);

// Deep compositing equals the serial reference at 1x1 and 17x13 for both fragment encodings, with
// empty pixels, lists up to 100 fragments, zero-opacity fragments and depth ties across ranks.
void checkSmallImages(comm::Communicator* comm, const vk::Context& ctx);
// The same at 256x256 (mostly short lists, a few of up to 100).
void checkLargeImage(comm::Communicator* comm, const vk::Context& ctx);
// A 2048x2049 image: one-dimensional passes over its pixels need more workgroups than one
// dispatch row holds (vk::groupGrid).
void checkBeyondOneDispatchRow(comm::Communicator* comm, const vk::Context& ctx);
// Fixed-K lists overflowing (K = 1 and 3): drop and merge against the host model of the device
// interface, composited against the serial reference.
void checkFixedLists(comm::Communicator* comm, const vk::Context& ctx);
// The counter width follows the longest list of any rank across the 2/4/8/32-bit boundaries;
// forcing a width gives the same image, forcing one too small fails on every rank.
void checkCounterBoundaries(comm::Communicator* comm, const vk::Context& ctx);
// Interleaved lists: single-fragment compositing differs visibly from deep (and matches its own
// model) while deep matches the serial reference.
void checkSingleFragment(comm::Communicator* comm, const vk::Context& ctx);
// Per-rank statistics, gathered statistics and heatmaps, bytes sent equal to the replay's.
void checkStatistics(comm::Communicator* comm, const vk::Context& ctx);
// Frames of varying size: correct each time; steady frames allocate no device buffers.
void checkBuffersOnlyGrow(comm::Communicator* comm, const vk::Context& ctx);
// Pixels with more non-empty lists than registerLists merge in memory, with the same result.
void checkMemoryMerge(comm::Communicator* comm, const vk::Context& ctx);

}  // namespace sm::comp::test
