// The far field: gmsh's tetrahedra between a box and the closed triangulated surfaces left open
// by the earlier stages (the capped boundary layer, the capped hexahedral block).
#pragma once

#include <functional>
#include <vector>

#include "gen/cfd_bodies.h"
#include "gen/volume_assembly.h"

namespace sm::gen {

// Meshes the box minus the surfaces (each closed) with tetrahedra of the given size and adds them
// and their new points to `a`. Points of the surfaces are shared, not duplicated.
void addFarField(VolumeAssembly& a, const Box& box, const std::vector<std::vector<Triangle>>& holes,
                 const std::function<double(const glm::dvec3&)>& size);

}  // namespace sm::gen
