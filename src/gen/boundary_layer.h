// The boundary layer: gmsh extrudes the wall mesh along its (smoothed) normals in a model of its
// own, giving wedges on wall triangles and hexahedra on wall quads.
#pragma once

#include <vector>

#include "gen/volume_assembly.h"
#include "gen/wall_mesh.h"

namespace sm::gen {

constexpr int kLayerCount = 4;
constexpr double kLayerGrowth = 1.3;         // each layer this much thicker than the one below
constexpr double kCapHeightFraction = 0.35;  // pyramid height / quad edge on the layer's outside

// Adds the layer's wedges and hexahedra (and the wall's and layer's points) to `a`, caps the
// layer's outer quads with pyramids, and returns the closed triangulated surface that is left
// for the tetrahedra: the layer's outer triangles and the pyramids' sides.
std::vector<Triangle> addBoundaryLayer(const WallMesh& wall, double thickness, VolumeAssembly& a);

}  // namespace sm::gen
