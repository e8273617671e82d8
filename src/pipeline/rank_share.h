// This rank's share of a data set: which clusters it renders, their elements merged into one mesh,
// and what every rank must agree on (global bounds, ranges, element size).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "border/cell_averager.h"
#include "comm/reductions.h"
#include "io/mesh_io.h"
#include "mesh/unstructured_mesh.h"
#include "scene/view_defaults.h"

namespace sm::app {

struct ShareOptions {
  io::ReadOptions read;
  int metisClusters = 0;  // > 0: split into this many clusters with METIS (ignores file clusters)
  // Keep one time step in memory and read the others from the file when they are needed (.vtu and
  // .pvtu and series of them; other formats are loaded whole, every step in memory). Cell data is
  // streamed too when each rank reads its own pieces or one rank reads the whole file
  // (streamsCellData), any number of fields.
  bool streamSteps = false;
  // Whether read.fields names cell data, when the caller has asked fieldsAreCellData already
  // (unset: loadRankShare asks, one header read and one collective).
  std::optional<bool> cellData;
};

// How a streamed share reads its other steps: io::readFieldStep(path, field, step, read,
// filePoints) gives them in the order of the share's mesh. Cell data comes from
// io::readCellFieldStep(path, field, step, read) and fileCells, averaged onto the points by `cells`
// with every rank's help (collective).
struct StepStream {
  io::ReadOptions read;
  std::vector<uint32_t> filePoints;             // empty: the file's points, in order
  std::vector<io::FieldStepCount> fieldSteps;   // of this rank's clusters
  std::vector<uint32_t> fileCells;              // cell data: UnstructuredMesh::cellOrigin
  uint64_t fileCellCount = 0;                   // and UnstructuredMesh::fileCells
  std::shared_ptr<border::CellAverager> cells;  // set when a field streamed is cell data
  std::vector<std::string> cellFields;          // those fields, the same on every rank
};

struct RankShare {
  mesh::UnstructuredMesh mesh;  // this rank's clusters, merged
  std::vector<int> clusters;    // cluster ids this rank renders
  int totalClusters = 0;
  mesh::Bounds wholeBounds;           // of the whole data set (all ranks)
  scene::ElementSizeSum elementSize;  // whole data set
  uint64_t wholeElements = 0;
  std::optional<StepStream> stream;  // set when the mesh holds one step per field
};

// True when read.fields names cell data (io::asksForCellData), decided by rank 0 for all ranks.
bool fieldsAreCellData(const std::string& path, const io::ReadOptions& read,
                       comm::Communicator& comm);

// True when loadRankShare streams cell data of `path` on `ranks` ranks with options o: the format
// reads steps alone, and each rank reads its own pieces (or one rank reads the whole file).
bool streamsCellData(const std::string& path, const ShareOptions& o, int ranks);

// Reads what this rank needs. A .pvtu is split by pieces: each rank reads only its own pieces
// (assigned to balance element counts, from the pieces' headers); cell data asked for as the field
// is then averaged onto the points with the sums of the other ranks at the points they share
// (cellDataToPointsOverRanks). Other formats are read whole on every rank and split by cluster id.
RankShare loadRankShare(const std::string& path, const ShareOptions& options,
                        comm::Communicator& comm);

}  // namespace sm::app
