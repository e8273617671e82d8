// C++ view of the shared cell table (shaders/shared/cell_tables.h).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "shared/cell_tables.h"

namespace sm::mesh {

enum class CellType : uint8_t { Tet = 0, Pyramid = 1, Wedge = 2, Hex = 3 };
inline constexpr int kNumCellTypes = 4;
inline constexpr std::array<CellType, 4> kAllCellTypes = {CellType::Tet, CellType::Pyramid,
                                                          CellType::Wedge, CellType::Hex};

constexpr uint32_t typeIndex(CellType t) {
  return static_cast<uint32_t>(t);
}
constexpr uint32_t numVerts(CellType t) {
  return gpu::SM_NUM_VERTS[typeIndex(t)];
}
constexpr uint32_t numFaces(CellType t) {
  return gpu::SM_NUM_FACES[typeIndex(t)];
}
constexpr uint32_t faceSize(CellType t, uint32_t f) {
  return gpu::smFaceSize(typeIndex(t), f);
}
constexpr uint32_t faceVert(CellType t, uint32_t f, uint32_t k) {
  return gpu::smFaceVert(typeIndex(t), f, k);
}

std::string_view cellTypeName(CellType t);        // "tetrahedron", ...
std::string_view cellTypePluralName(CellType t);  // "tetrahedra", ...

// VTK cell type code -> our type for the four linear volume cells.
std::optional<CellType> fromVtkType(int vtkType);
int toVtkType(CellType t);

}  // namespace sm::mesh
