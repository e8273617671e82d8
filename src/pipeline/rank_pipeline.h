// Preparation through the cache and upload: what render, view and bench share.
#pragma once

#include <memory>
#include <string>

#include "pipeline/rank_share.h"
#include "prep/prepare.h"
#include "render/gpu_scene.h"

namespace sm::app {

struct PreparedShare {
  prep::PreparedRank rank;
  prep::PrepTimings timings;
  bool fromCache = false;
};

// Prepares this rank's mesh (taking its geometry out of `share.mesh`), reading and writing the
// binary cache in cacheDir when it is not empty. Stale or corrupt caches are rebuilt.
PreparedShare prepareShare(RankShare& share, const prep::PrepOptions& options,
                           const std::string& cacheDir, int rank, int ranks);

// Values of field `name` at `step` in this rank's vertex order; throws listing the fields there
// are.
std::vector<float> fieldStep(const mesh::UnstructuredMesh& mesh, const prep::PreparedRank& rank,
                             const std::string& name, uint64_t step);

}  // namespace sm::app
