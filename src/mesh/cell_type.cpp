#include "mesh/cell_type.h"

namespace sm::mesh {

std::string_view cellTypeName(CellType t) {
  switch (t) {
    case CellType::Tet:
      return "tetrahedron";
    case CellType::Pyramid:
      return "pyramid";
    case CellType::Wedge:
      return "wedge";
    case CellType::Hex:
      return "hexahedron";
  }
  return "?";
}

std::string_view cellTypePluralName(CellType t) {
  switch (t) {
    case CellType::Tet:
      return "tetrahedra";
    case CellType::Pyramid:
      return "pyramids";
    case CellType::Wedge:
      return "wedges";
    case CellType::Hex:
      return "hexahedra";
  }
  return "?";
}

std::optional<CellType> fromVtkType(int vtkType) {
  switch (vtkType) {
    case gpu::SM_VTK_TETRA:
      return CellType::Tet;
    case gpu::SM_VTK_PYRAMID:
      return CellType::Pyramid;
    case gpu::SM_VTK_WEDGE:
      return CellType::Wedge;
    case gpu::SM_VTK_HEXAHEDRON:
      return CellType::Hex;
    default:
      return std::nullopt;
  }
}

int toVtkType(CellType t) {
  constexpr int codes[4] = {gpu::SM_VTK_TETRA, gpu::SM_VTK_PYRAMID, gpu::SM_VTK_WEDGE,
                            gpu::SM_VTK_HEXAHEDRON};
  return codes[typeIndex(t)];
}

}  // namespace sm::mesh
