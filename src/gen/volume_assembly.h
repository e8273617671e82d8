// The CFD mesh is assembled in stages: gmsh's boundary layer on the wall, pyramids capping the
// layer's outer quads (and the faces of the optional hexahedral block), then gmsh's tetrahedra
// filling the far field up to the triangles those stages leave open. The stages share points and
// cells here, in VTK vertex order, before one MeshBuilder pass turns them into the mesh.
//
// The pyramids are ours rather than gmsh's: gmsh 4.8 builds pyramids on quads by relocating a
// vertex from the quad's centre, which on thin, curved boundary layers leaves flat pyramids that
// overlap the hexahedron below (seen on the capsule's afterbody at every size).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/unstructured_mesh.h"

namespace sm::gen {

using Triangle = std::array<uint32_t, 3>;
using Quad = std::array<uint32_t, 4>;

struct VolumeAssembly {
  std::vector<glm::dvec3> points;
  std::array<std::vector<uint32_t>, mesh::kNumCellTypes> cells;  // VTK order

  uint32_t addPoint(const glm::dvec3& p);
  // Adds a cell as given: VTK order, positively oriented (MeshBuilder counts any that is not).
  void addCell(mesh::CellType type, std::span<const uint32_t> ids);
  mesh::UnstructuredMesh build(const std::string& source) const;
};

// Puts a pyramid on each quad, its apex on the side away from `inside[i]` (a point behind quad i)
// at `heightFraction` of the quad's mean edge length, and returns the pyramids' four side
// triangles per quad: the surface the tetrahedra attach to.
std::vector<Triangle> capQuads(VolumeAssembly& a, const std::vector<Quad>& quads,
                               const std::vector<glm::dvec3>& inside, double heightFraction);

// A structured block of hexahedra filling `lo`..`hi` with cells of about `size`, capped with
// pyramids on its faces; returns the caps' triangles.
std::vector<Triangle> addHexBlock(VolumeAssembly& a, const glm::dvec3& lo, const glm::dvec3& hi,
                                  double size);

}  // namespace sm::gen
