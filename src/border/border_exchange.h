// Points a rank shares with other ranks, found by their coordinates, and per-point sums added up
// across them: how cell data held piece by piece (a .pvtu's pieces, a simulation's partition) is
// averaged onto the points as if one process held the whole mesh (mesh::cellFieldsToPoints).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "comm/reductions.h"
#include "mesh/unstructured_mesh.h"

namespace sm::border {

class BorderExchange {
 public:
  // Collective. In a conforming mesh only points on the boundary of a rank's elements (faces no
  // other element of that rank has) can be used by another rank's elements. Each is named by its
  // coordinates, bit for bit, and its occurrence among this rank's points at those coordinates
  // (the k-th copy of a point in the pieces joins the k-th copy elsewhere, as the weld joins a
  // .pvtu's pieces: io::weldPieces), and sent to a meeting rank chosen by a hash of that name;
  // the meeting rank tells each sender which of its points another rank has too. Traffic is
  // proportional to the boundary, whatever the shape of the parts. Throws sm::Error naming the
  // mesh for faces shared by more than two elements (as preparation would).
  //
  // `pointIds`, when not empty (one per point, the same on every rank for one point: a solver's
  // global vertex numbers), name the points instead of their coordinates: two points at one
  // position with different ids (a baffle's sides, each on its own rank) stay apart.
  BorderExchange(const mesh::UnstructuredMesh& m, comm::Communicator& comm,
                 std::span<const uint64_t> pointIds = {});

  // Collective. Each of `columns` holds one value per point of this rank. Replaces each shared
  // point's values by the sums of the values of every rank's copy of the point, added in rank
  // order at its meeting rank, so that every copy gets the same values, bit for bit. Every rank
  // calls it the same number of times with the same number of columns.
  void addOtherRanks(std::vector<std::vector<double>>& columns, comm::Communicator& comm) const;

  uint64_t sharedPoints() const { return sharedPoints_; }  // of this rank: on another rank too

 private:
  uint64_t numPoints_ = 0;
  std::vector<std::vector<uint32_t>> mine_;     // [meeting rank]: this rank's shared points
  std::vector<std::vector<uint32_t>> groupOf_;  // as meeting rank, [sender][i]: the point's group
  uint64_t groups_ = 0;
  uint64_t sharedPoints_ = 0;
};

}  // namespace sm::border
