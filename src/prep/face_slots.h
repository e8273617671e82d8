// Face slots: every element face of a rank, numbered type by type (tets, pyramids, wedges,
// hexahedra), element by element. Shared by connectivity matching and shell extraction.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "mesh/cell_type.h"

namespace sm::prep {

using ElementArrays = std::array<std::vector<uint32_t>, mesh::kNumCellTypes>;

// VTK face of a tetrahedron opposite local vertex i (face slots of tets are by opposite vertex).
inline constexpr uint32_t kTetFaceOpposite[4] = {1, 2, 0, 3};

class FaceSlots {
 public:
  explicit FaceSlots(const ElementArrays& elements);
  uint64_t total() const { return begin_[mesh::kNumCellTypes]; }
  uint64_t begin(uint32_t type) const { return begin_[type]; }
  uint64_t elements(uint32_t type) const { return count_[type]; }

  struct Slot {
    uint32_t type;
    uint32_t element;
    uint32_t slot;
  };
  Slot decode(uint64_t g) const;

  // The VTK face number behind slot `slot` of an element with ids v (identity except for tets).
  static uint32_t vtkFace(uint32_t type, const uint32_t* v, uint32_t slot);
  // Vertex ids of the face in outward cyclic order; returns 3 or 4.
  static uint32_t faceVertices(uint32_t type, const uint32_t* v, uint32_t slot, uint32_t out[4]);

 private:
  std::array<uint64_t, mesh::kNumCellTypes + 1> begin_{};
  std::array<uint64_t, mesh::kNumCellTypes> count_{};
};

}  // namespace sm::prep
