// What a read asks for (ReadOptions) and what it finds (FieldStepCount): shared by every reader,
// the VTK formats' (src/io) and the solvers' (src/solver_io), and by io::readMesh, which chooses
// between them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "io_core/read_stop.h"

namespace sm::io {

struct ReadOptions {
  // Point fields to load. "NAME" loads a scalar array, or the magnitude of a vector array;
  // "NAME[k]" loads component k. Empty: every point array (vectors as magnitudes). A name the
  // file does not have is an error that lists the names it has.
  std::vector<std::string> fields;
  bool loadFields = true;
  // Cell array holding cluster ids. Empty: the first of "cluster", "partition", "vtkProcessId"
  // present; else every cell is cluster 0. For .pvtu, piece i is cluster i, and a name is an error.
  std::string clusterArray;
  // .pvtu only: read just these pieces (cluster ids stay the global piece numbers). Empty: all.
  std::vector<int> pieces;
  // Threads for decompression and conversions (0: all cores; 1 for per-core measurements).
  unsigned threads = 0;
  // Load only this time step of every field, as the field's one step (a field with fewer steps:
  // its last), so that memory does not grow with the number of steps; later steps are read with
  // readFieldStep. Unset: every step.
  std::optional<uint64_t> step;
  // Cell data named in `fields` is averaged onto the points of the mesh read (the mesh returned has
  // no cellFields). False: it is left in mesh.cellFields, for a caller that has read only some of
  // a .pvtu's pieces to average with the help of the ranks holding the others.
  bool cellDataOnPoints = true;
  // .vtu, .pvtu and series of them: record where each element came from (mesh.cellOrigin), so
  // that later steps of cell data can be read alone (readCellFieldStep).
  bool cellOrigins = false;
  // Stops the read with io::ReadStopped (read_stop.h) once it returns true. It is asked before
  // each piece, each file of a series, each section of a legacy or .ugrid file and each
  // compressed block, so a stop waits for one such unit of work at most.
  StopRequested stopRequested;
};

// A point field a read loads and its number of time steps.
struct FieldStepCount {
  std::string name;
  uint64_t steps = 0;
  bool cellData = false;    // read as cell data (named by the request), averaged onto the points
  uint32_t components = 0;  // of the array read whole (a vector's magnitude); 0: one component
                            // of it ("p[1]"), or not known
};

// options.pieces checked against `count` (sm::FileError naming `path` for one out of range or
// given twice) and sorted; every piece when empty.
std::vector<int> choosePieces(const std::string& path, size_t count, const ReadOptions& options);

}  // namespace sm::io
