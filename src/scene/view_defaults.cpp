#include "scene/view_defaults.h"

#include <cmath>
#include <span>

#include "mesh/element_geometry.h"

namespace sm::scene {

ElementSizeSum elementSizeSum(const mesh::UnstructuredMesh& m) {
  ElementSizeSum s;
  for (mesh::CellType t : mesh::kAllCellTypes) {
    const uint32_t nv = mesh::numVerts(t);
    const auto& cells = m.cells[mesh::typeIndex(t)];
    for (size_t e = 0; e + nv <= cells.size(); e += nv) {
      double v =
          std::abs(mesh::signedVolume(t, std::span<const uint32_t>(&cells[e], nv), m.points));
      s.sum += std::cbrt(v);
      ++s.count;
    }
  }
  return s;
}

}  // namespace sm::scene
