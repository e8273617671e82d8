// Cell data one step at a time (one value per element, as finite-volume solvers hold their
// unknowns: a simulation's in situ, a file's streamed step by step), averaged onto the vertices
// over the elements of every rank that use them: what a one-process run over the whole mesh would
// give (mesh::cellFieldsToPoints, ParaView's Cell Data to Point Data), so that a partition's
// borders leave no seam in the image.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "border/border_exchange.h"
#include "mesh/unstructured_mesh.h"

namespace sm::border {

class CellAverager {
 public:
  CellAverager() = default;  // no mesh yet
  // Keeps the points and cells of this rank's mesh, before preparation takes them (4 bytes per
  // element vertex, 24 per vertex and 8 per global id): the values of a later call are summed at
  // its vertices. The first call frees the points and ids. globalIds: one per vertex, a solver's
  // global numbers (empty: shared vertices are found by their coordinates).
  CellAverager(const mesh::UnstructuredMesh& input, std::vector<uint64_t> globalIds = {});

  uint64_t numCells() const { return numCells_; }
  // Collective: every rank calls it, with its own cells' values in the mesh's order (tetrahedra,
  // then pyramids, wedges, hexahedra). Returns one value per vertex of the mesh's points: the mean
  // of the values of the elements, on every rank, that use it (NaN for a vertex no element uses;
  // a NaN element makes its vertices NaN). The first call finds the vertices shared with other
  // ranks (by their coordinates, bit for bit) and counts the elements at each.
  std::vector<float> toPoints(std::span<const float> values, comm::Communicator& comm);

 private:
  void findSharedPoints(comm::Communicator& comm);

  mesh::UnstructuredMesh mesh_;  // points and cells only
  std::vector<uint64_t> globalIds_;
  uint64_t numPoints_ = 0, numCells_ = 0;
  bool found_ = false;  // findSharedPoints has run (collective: a flag, not a size test)
  std::unique_ptr<BorderExchange> border_;  // null on one rank: nothing is shared
  std::vector<double> uses_;                // elements at each vertex, every rank's
};

}  // namespace sm::border
