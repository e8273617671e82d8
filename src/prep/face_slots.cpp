#include "prep/face_slots.h"

#include "common/check.h"

namespace sm::prep {

FaceSlots::FaceSlots(const ElementArrays& elements) {
  for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t) {
    count_[t] = elements[t].size() / gpu::SM_NUM_VERTS[t];
    begin_[t + 1] = begin_[t] + count_[t] * gpu::SM_NUM_FACES[t];
  }
}

uint32_t FaceSlots::vtkFace(uint32_t type, const uint32_t* v, uint32_t slot) {
  if (type != gpu::SM_TET) return slot;
  // The vertex whose rank among the four ids is `slot`.
  for (uint32_t i = 0; i < 4; ++i) {
    uint32_t rank = 0;
    for (uint32_t j = 0; j < 4; ++j) rank += v[j] < v[i];
    if (rank == slot) return kTetFaceOpposite[i];
  }
  SM_CHECK_MSG(false, "tetrahedron with repeated vertex ids");
  return 0;
}

uint32_t FaceSlots::faceVertices(uint32_t type, const uint32_t* v, uint32_t slot, uint32_t out[4]) {
  uint32_t f = vtkFace(type, v, slot);
  uint32_t n = gpu::smFaceSize(type, f);
  for (uint32_t k = 0; k < n; ++k) out[k] = v[gpu::smFaceVert(type, f, k)];
  return n;
}

}  // namespace sm::prep
