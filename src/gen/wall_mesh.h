// The body's surface mesh, carried from the OpenCASCADE model (where gmsh can mesh the solid's
// faces) into the built-in kernel model that extrudes the boundary layer. Faces are oriented here
// so that every normal points out of the body: the layer grows along the normals, and faces that
// disagree with their neighbours would fold it.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

namespace sm::gen {

struct WallMesh {
  std::vector<std::size_t> nodeTags;
  std::vector<double> coords;          // 3 per node
  std::vector<std::size_t> triangles;  // 3 node tags each
  std::vector<std::size_t> quads;      // 4 node tags each
};

// Meshes the boundary of the body volume `volume` in the current model with elements of the given
// size (quads on the surfaces in `recombine`) and returns its faces, oriented outward. Throws
// GmshError when the surface mesh is not a closed two-manifold (gmsh can produce such meshes at
// coarse sizes).
WallMesh meshWall(int volume, const std::vector<int>& recombine,
                  const std::function<double(const glm::dvec3&)>& size);

}  // namespace sm::gen
