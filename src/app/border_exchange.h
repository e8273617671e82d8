// Points a rank shares with other ranks, found by their coordinates, and per-point sums added up
// across them: how cell data read piece by piece is averaged onto the points as if the whole mesh
// had been read (mesh::cellFieldsToPoints), without any rank reading the whole mesh.
#pragma once

#include <cstdint>
#include <vector>

#include "app/collectives.h"
#include "mesh/unstructured_mesh.h"

namespace sm::app {

class BorderExchange {
 public:
  // Collective. Only points on the boundary of this rank's elements (faces no other local element
  // shares) can be used by another rank's elements in a conforming mesh; those are offered to the
  // ranks whose boundary's bounding box holds them, and matched there by bitwise-equal coordinates,
  // as the weld matches the points of a .pvtu's pieces. Throws sm::Error naming the mesh for faces
  // shared by more than two elements (as preparation would).
  BorderExchange(const mesh::UnstructuredMesh& m, Collectives& coll);

  // Collective. Adds to each of this rank's points the values (one per point, in each rank's own
  // point order) of the coincident points of the other ranks. Every rank calls it the same number
  // of times.
  void addOtherRanks(std::vector<double>& perPoint, Collectives& coll) const;

  uint64_t sharedPoints() const { return shared_; }  // of this rank: matched on another rank

 private:
  std::vector<std::vector<uint32_t>> send_;  // [rank]: this rank's points offered to it, in order
  std::vector<std::vector<int64_t>> match_;  // [rank]: where each point it offers adds, or -1
  uint64_t shared_ = 0;
};

// Averages the cell fields of a rank's share (read with io::ReadOptions::cellDataOnPoints false)
// onto its points, the cells of every rank counted: the result equals what the whole mesh's
// mesh::cellFieldsToPoints gives those points, up to the order of summation. Collective; ranks
// holding no elements take part with an empty mesh. Throws sm::Error when ranks disagree about
// the cell fields' names or step counts.
void cellDataToPointsOverRanks(mesh::UnstructuredMesh& m, Collectives& coll);

}  // namespace sm::app
