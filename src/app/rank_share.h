// This rank's share of a data set: which clusters it renders, their elements merged into one mesh,
// and what every rank must agree on (global bounds, ranges, element size).
#pragma once

#include <string>
#include <vector>

#include "app/collectives.h"
#include "io/mesh_io.h"
#include "mesh/unstructured_mesh.h"
#include "render/frame_defaults.h"

namespace sm::app {

struct ShareOptions {
  io::ReadOptions read;
  int metisClusters = 0;  // > 0: split into this many clusters with METIS (ignores file clusters)
};

struct RankShare {
  mesh::UnstructuredMesh mesh;  // this rank's clusters, merged
  std::vector<int> clusters;    // cluster ids this rank renders
  int totalClusters = 0;
  mesh::Bounds wholeBounds;            // of the whole data set (all ranks)
  render::ElementSizeSum elementSize;  // whole data set
  uint64_t wholeElements = 0;
};

// Reads what this rank needs. A .pvtu is split by pieces: each rank reads only its own pieces
// (assigned to balance element counts, from the pieces' headers). Other formats are read whole
// on every rank and split by cluster id.
RankShare loadRankShare(const std::string& path, const ShareOptions& options, Collectives& coll);

}  // namespace sm::app
