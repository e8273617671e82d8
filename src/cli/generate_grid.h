// `generate --method grid`: the procedural O-grid mesh (gen/grid_mesh.h) written piece by piece,
// pieces on all cores at once, after checking that the disk and memory can take it.
#pragma once

#include <cstdint>
#include <string>

#include "gen/grid_mesh.h"

namespace sm::app {

struct GridGenerateArgs {
  uint64_t elements = 0;
  int clusters = 0;  // 0: the generator's choice
  int steps = 1;
  bool cellData = false;
  bool compress = false;
  std::string out;  // .pvtu
};

// Writes the mesh and returns the summary line `generate` prints. Throws sm::Error naming the
// option or the file before anything is written when the data cannot fit the disk or memory.
std::string generateGridMesh(const GridGenerateArgs& args);

// Bytes the written files need, at most (uncompressed; pieces repeat the points they share).
uint64_t gridFileBytes(const gen::GridMesh& grid, int steps, bool cellData);

}  // namespace sm::app
