// Per-rank preparation: global vertex order and rebasing, connectivity, shell, compaction.
#pragma once

#include <span>
#include <string>

#include "mesh/unstructured_mesh.h"
#include "prep/connectivity.h"
#include "prep/prepared_rank.h"

namespace sm::prep {

struct PrepTimings {
  double vertexOrder = 0, connectivity = 0, shell = 0, compaction = 0;  // seconds
  double total() const { return vertexOrder + connectivity + shell + compaction; }
};

struct PrepResult {
  PreparedRank rank;
  PrepTimings timings;
  ConnectivityStats connectivity;
};

// Prepares one rank's mesh. Takes the geometry out of `mesh` (points and cells are moved out and
// released as soon as they are converted, and the cells' cluster ids with them, to keep peak
// memory low); fields and the rest stay for the caller. The frame must be the same on every rank.
PrepResult prepareRank(mesh::UnstructuredMesh& mesh, const GlobalFrame& frame,
                       const PrepOptions& options);

// The sizes of one rank's scene that its shaders index with 32-bit integers (SPIR-V may read them
// as signed, so every word index stays below 2^31): records and neighbours of each element type
// (per the encoding), 16-byte vertex records, and 3 indices per shell triangle. Throws naming
// `source` and what is too large; prepareRank checks this as soon as each size is known.
struct SceneSizes {
  uint64_t elements[4] = {0, 0, 0, 0};  // per type, in SM_TET .. SM_HEX order
  uint64_t vertices = 0;
  uint64_t shellTriangles = 0;
};
void checkShaderIndexRange(const std::string& source, const SceneSizes& sizes, bool compact);

// The largest sizes checkShaderIndexRange accepts: the words of the largest array of each (word
// indices up to 2^31 - 1), divided by the words per item. An element's array is its records or
// its neighbours (one per face), whichever has more words per element.
inline constexpr uint64_t kMaxShaderWords = (uint64_t(1) << 31) - 1;
constexpr uint64_t maxElementsOnRank(uint32_t type, bool compact) {
  const uint64_t record =
      compact && type != gpu::SM_HEX ? gpu::SM_COMPACT_WORDS[type] : gpu::SM_PLAIN_WORDS[type];
  return kMaxShaderWords / (record > gpu::SM_NUM_FACES[type] ? record : gpu::SM_NUM_FACES[type]);
}
inline constexpr uint64_t kMaxVerticesOnRank = kMaxShaderWords / 4;        // 16-byte records
inline constexpr uint64_t kMaxShellTrianglesOnRank = kMaxShaderWords / 3;  // 3 indices each

// One step of one field in this rank's vertex order (what the GPU scalar buffer holds).
std::vector<float> gatherScalars(const PreparedRank& rank, std::span<const float> meshValues);

}  // namespace sm::prep
