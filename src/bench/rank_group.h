// In-process ranks for benchmarks: a mesh split into METIS clusters dealt round-robin to N ranks
// (interleaved, non-convex shares, several fragments per pixel and rank), each rank a thread with
// its own Vulkan context, compositing through a LocalCommunicator exactly as MPI ranks would.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "compositor/deep_compositor.h"
#include "mesh/unstructured_mesh.h"
#include "render/render_settings.h"
#include "scene/image.h"

namespace sm::app::bench {

struct GroupFrame {
  double ms = 0;  // median wall time of a warm frame, slowest rank
  scene::Image image;
  double fragmentsPerPixel = 0;  // all ranks' fragments over the pixels the image covers
  uint64_t overflow = 0;         // fixed-K lists: fragments dropped or merged
  uint64_t lostRays = 0;
};

// How clusters are dealt to ranks: round-robin (interleaved shares), or all on rank 0 (the others
// hold nothing: the exchange's overhead over one rank's work).
enum class Dealing { RoundRobin, AllOnRankZero };

class RankGroup {
 public:
  // Splits `whole` (its field `field`, step 0) into `clusters` METIS clusters over `ranks` ranks.
  RankGroup(const mesh::UnstructuredMesh& whole, const std::string& field, int ranks, int clusters,
            const std::string& device, Dealing dealing = Dealing::RoundRobin);
  ~RankGroup();
  RankGroup(const RankGroup&) = delete;
  RankGroup& operator=(const RankGroup&) = delete;

  int ranks() const;
  // One cold frame, then `runs` warm frames of every rank; the image and statistics of the last.
  GroupFrame render(const render::RenderSettings& settings, const comp::CompositorOptions& lists,
                    int runs);

 private:
  struct Shares;
  std::unique_ptr<Shares> shares_;
  std::string device_;
};

}  // namespace sm::app::bench
