#include "border/cell_averager.h"

#include <utility>

#include "common/check.h"

namespace sm::border {

CellAverager::CellAverager(const mesh::UnstructuredMesh& input, std::vector<uint64_t> globalIds)
    : globalIds_(std::move(globalIds)), numPoints_(input.numPoints()), numCells_(input.numCells()) {
  mesh_.source = input.source;
  mesh_.points = input.points;
  mesh_.cells = input.cells;
}

void CellAverager::findSharedPoints(RankExchange& ranks) {
  found_ = true;
  uses_ = mesh::cellUsesAtPoints(mesh_);
  if (ranks.size() > 1) {
    border_ = std::make_unique<BorderExchange>(mesh_, ranks, globalIds_);
    std::vector<std::vector<double>> columns{std::move(uses_)};
    border_->addOtherRanks(columns, ranks);
    uses_ = std::move(columns[0]);
  }
  // Positions and ids only name the shared points: from here on the cells suffice.
  std::vector<glm::dvec3>().swap(mesh_.points);
  std::vector<uint64_t>().swap(globalIds_);
}

std::vector<float> CellAverager::toPoints(std::span<const float> values, RankExchange& ranks) {
  SM_CHECK_EQ(values.size(), numCells_);
  if (!found_) findSharedPoints(ranks);
  std::vector<std::vector<double>> sums(1, std::vector<double>(numPoints_, 0.0));
  size_t cell = 0;
  for (int t = 0; t < mesh::kNumCellTypes; ++t) {
    const uint32_t nv = mesh::numVerts(mesh::kAllCellTypes[t]);
    const std::vector<uint32_t>& ids = mesh_.cells[t];
    for (size_t i = 0; i < ids.size(); i += nv, ++cell)
      for (uint32_t k = 0; k < nv; ++k) sums[0][ids[i + k]] += values[cell];
  }
  if (border_) border_->addOtherRanks(sums, ranks);
  return mesh::meansAtPoints(sums[0], uses_);
}

}  // namespace sm::border
