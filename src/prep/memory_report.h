// Per-rank memory report: what preparation keeps, by structure, and what compaction saves.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "prep/prepared_rank.h"

namespace sm::prep {

struct MemoryReport {
  uint64_t vertices = 0;      // rebased float positions
  uint64_t vertexMap = 0;     // rank vertex -> mesh vertex (host only, for scalar gathers)
  uint64_t connectivity = 0;  // one neighbour reference per face
  uint64_t shell = 0;         // triangle indices, element refs, edge adjacency (+ quad 4th vertex)
  uint64_t compactedElements = 0;  // XOR records (what compact mode keeps)
  uint64_t plainElements = 0;      // VTK-ordered ids (what plain mode keeps)
  uint64_t scalarsPerStep = 0;
  uint64_t scalarSteps = 0;             // steps resident
  uint64_t accelerationStructures = 0;  // shell BLAS + TLAS, filled in by the renderer
  bool compact = true;

  uint64_t elementBytes() const { return compact ? compactedElements : plainElements; }
  // Everything the rank keeps for rendering (device side), in bytes.
  uint64_t preparedBytes() const;
  // Element index memory saved by compaction: 1 - compacted / plain (the paper reports 72.49%).
  double compactionSavings() const;
  // As the paper's figure: share of connectivity, elements and shell in preparedBytes.
  std::string table() const;
};

MemoryReport memoryReport(const PreparedRank& rank, uint64_t scalarSteps = 1);
void to_json(nlohmann::json& j, const MemoryReport& m);

std::string formatBytes(uint64_t bytes);

}  // namespace sm::prep
