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
  // Inline, with constant divisors: connectivity decodes every face slot, and an out-of-line call
  // dividing by a divisor read from a table was an eighth of preparation's time (measured in
  // commit 2e30e1d).
  Slot decode(uint64_t g) const {
    uint32_t t = 0;
    while (g >= begin_[t + 1]) ++t;
    const uint64_t local = g - begin_[t];
    static_assert(gpu::SM_NUM_FACES[gpu::SM_TET] == 4 && gpu::SM_NUM_FACES[gpu::SM_PYR] == 5 &&
                  gpu::SM_NUM_FACES[gpu::SM_WED] == 5 && gpu::SM_NUM_FACES[gpu::SM_HEX] == 6);
    switch (t) {
      case gpu::SM_TET:
        return {t, uint32_t(local / 4), uint32_t(local % 4)};
      case gpu::SM_PYR:
      case gpu::SM_WED:
        return {t, uint32_t(local / 5), uint32_t(local % 5)};
      default:
        return {t, uint32_t(local / 6), uint32_t(local % 6)};
    }
  }

  // The VTK face number behind slot `slot` of an element with ids v (identity except for tets).
  static uint32_t vtkFace(uint32_t type, const uint32_t* v, uint32_t slot);
  // Vertex ids of the face in outward cyclic order; returns 3 or 4.
  static uint32_t faceVertices(uint32_t type, const uint32_t* v, uint32_t slot, uint32_t out[4]);

 private:
  std::array<uint64_t, mesh::kNumCellTypes + 1> begin_{};
  std::array<uint64_t, mesh::kNumCellTypes> count_{};
};

}  // namespace sm::prep
