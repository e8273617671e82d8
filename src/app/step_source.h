// Where a rank's field steps come from while it renders a sequence: the file, one step at a time
// (a streamed share, see RankShare::stream), or the mesh in memory. Steps are handed out in the
// prepared vertex order, ready for the GPU.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "app/rank_share.h"
#include "prep/prepared_rank.h"

namespace sm::app {

class StepSource {
 public:
  // Call before preparation takes the points out of share.mesh; `share` must outlive the source.
  StepSource(const std::string& path, const RankShare& share);

  // Steps of `field` on this rank (0 when its clusters lack the field).
  uint64_t numSteps(const std::string& field) const;
  // Range of one step over this rank's points (empty when it lacks the field or the step).
  mesh::Range range(const std::string& field, uint64_t step) const;
  // One step in `rank`'s vertex order (empty for a rank without vertices); throws naming --field
  // when the field is missing, as app::fieldStep does. Reads files only, so it may run on a
  // thread of its own while frames render. `threads` decompress and convert (0: the read
  // options' count).
  std::vector<float> scalars(const prep::PreparedRank& rank, const std::string& field,
                             uint64_t step, unsigned threads = 0) const;

 private:
  std::vector<float> read(const std::string& field, uint64_t step, unsigned threads = 0) const;

  std::string path_;
  const RankShare& share_;
  uint64_t numPoints_;
};

}  // namespace sm::app
