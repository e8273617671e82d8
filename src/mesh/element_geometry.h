// Geometric predicates on single elements, in double precision.
#pragma once

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "mesh/cell_type.h"

namespace sm::mesh {

// Volume enclosed by the element's faces as the face table winds them (quads split by the shared
// rule), by the divergence theorem. Negative for an inverted element, near zero for a degenerate
// one.
double signedVolume(CellType t, std::span<const uint32_t> ids, std::span<const glm::dvec3> points);

// Permutes a VTK-ordered element into its mirror image (the same cell with opposite orientation):
// tet 1<->2; pyramid 1<->3; wedge 1<->2, 4<->5; hexahedron 1<->3, 5<->7.
void mirrorElement(CellType t, std::span<uint32_t> ids);

// True when two vertex ids of the element are equal.
bool hasRepeatedVertex(CellType t, std::span<const uint32_t> ids);

}  // namespace sm::mesh
