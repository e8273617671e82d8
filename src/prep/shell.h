// Shell extraction (the paper's "Per-Node Shell Generation"): every face without a neighbour on
// this rank, wound outward, quads split by the shared rule, sorted spatially.
#pragma once

#include <cstdint>
#include <vector>

#include "prep/face_slots.h"

namespace sm::prep {

struct Shell {
  std::vector<uint32_t> indices;  // 3 per triangle
  std::vector<uint32_t> refs;     // element behind each triangle (index << 2 | type)
  std::vector<uint32_t> other;    // 4th quad vertex per triangle, ~0u for triangle faces
};

// For triangle i and edge k (vertices k, k+1 mod 3), the shell triangle on the other side of that
// edge, or ~0u (open or non-manifold edge). The GPU walks this when the hardware's entry triangle
// and the exact crossing predicate disagree about a ray that passes within rounding of an edge.
std::vector<uint32_t> shellAdjacency(const std::vector<uint32_t>& indices);

// positions: rebased float xyz of this rank's vertices (for the spatial sort).
Shell extractShell(const ElementArrays& elements, const ElementArrays& neighbors,
                   const std::vector<float>& positions);

// Reorders triangles by the Morton code of their centroids. Lavapipe's BVH builder splits the
// triangle list in index order: unsorted shells trace hundreds of times slower (docs/DESIGN.md).
void sortShellSpatially(Shell& shell, const std::vector<float>& positions);

}  // namespace sm::prep
