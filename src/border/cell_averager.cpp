#include "border/cell_averager.h"

#include <utility>

#include "common/check.h"

namespace sm::border {

CellAverager::CellAverager(const mesh::UnstructuredMesh& input, std::vector<uint64_t> globalIds)
    : globalIds_(std::move(globalIds)), numPoints_(input.numPoints()), numCells_(input.numCells()) {
  mesh_.source = input.source;
  mesh_.points = input.points;
  mesh_.cells = input.cells;
  // A polyhedron's tetrahedra count once at a point (mesh::cellUsesAtPoints).
  mesh_.cellOrigin = input.cellOrigin;
  mesh_.skipped.polyhedraSplit = input.skipped.polyhedraSplit;
}

void CellAverager::findSharedPoints(comm::Communicator& comm) {
  found_ = true;
  uses_ = mesh::cellUsesAtPoints(mesh_);
  if (comm.size() > 1) {
    border_ = std::make_unique<BorderExchange>(mesh_, comm, globalIds_);
    std::vector<std::vector<double>> columns{std::move(uses_)};
    border_->addOtherRanks(columns, comm);
    uses_ = std::move(columns[0]);
  }
  // Positions and ids only name the shared points: from here on the cells suffice.
  std::vector<glm::dvec3>().swap(mesh_.points);
  std::vector<uint64_t>().swap(globalIds_);
}

std::vector<float> CellAverager::toPoints(std::span<const float> values, comm::Communicator& comm) {
  SM_CHECK_EQ(values.size(), numCells_);
  if (!found_) findSharedPoints(comm);
  std::vector<std::vector<double>> sums(1, mesh::cellSumsAtPoints(mesh_, values, numPoints_));
  if (border_) border_->addOtherRanks(sums, comm);
  return mesh::meansAtPoints(sums[0], uses_);
}

}  // namespace sm::border
