// Firing explicit rays through the GPU renderer and the CPU reference, for hard-case tests.
#pragma once

#include <string>
#include <vector>

#include "mesh/unstructured_mesh.h"
#include "render/renderer.h"
#include "shared/render_types.h"

namespace sm::test {

// At least `random` random rays from outside the bounds, plus axis-aligned rays through every
// vertex column and along every edge direction of a grid with `gridCells` cells per side over the
// bounds, plus rays aimed exactly at vertices, edge midpoints and face centres of the mesh.
std::vector<render::WorldRay> hardRays(const mesh::UnstructuredMesh& mesh, int random,
                                       int gridCells, uint32_t seed);

struct RayComparison {
  uint64_t rays = 0, lost = 0, stepLimit = 0, nanRays = 0;
  double maxColorError = 0;  // composited RGBA of each ray, GPU vs reference, beyond sample ties
  // Rays whose only difference is one sample lying within float rounding of an element boundary
  // (float and double may decide t_k < t_out differently): at most one sample's opacity.
  uint64_t sampleTies = 0;
  double maxDepthError = 0;             // first significant fragment's depth
  uint64_t segmentCountMismatches = 0;  // rays whose count of significant fragments differs
  size_t worstRay = 0;                  // index of the ray with the largest colour error
  std::string worst;              // both renderers' fragments of that ray, for failure messages
  std::vector<double> rayErrors;  // per ray, max over RGBA (for distributions)
};

// Renders `rays` on the GPU (one rank) and with the CPU reference (Grid mode), ray by ray.
RayComparison compareRays(const mesh::UnstructuredMesh& mesh, const std::vector<float>& values,
                          const render::RenderSettings& settings,
                          const std::vector<render::WorldRay>& rays);

}  // namespace sm::test
