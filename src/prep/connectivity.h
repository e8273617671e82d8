// Connectivity by face matching (the paper's "Connectivity Generation"): one neighbour per
// element face, found by bucketing faces by their smallest vertex id (a counting sort) and
// matching equal vertex sets inside each bucket. O(faces) time, 4 bytes per face of scratch.
#pragma once

#include <functional>
#include <string>

#include <glm/vec3.hpp>

#include "prep/face_slots.h"

namespace sm::prep {

struct ConnectivityStats {
  uint64_t interiorFaces = 0;  // matched pairs
  uint64_t boundaryFaces = 0;  // faces with no neighbour on this rank (the shell)
};

// Where vertex v lies in the input's coordinates (for messages: element numbers after
// preparation's reordering mean nothing to a user, a position does).
using VertexPosition = std::function<glm::dvec3(uint32_t)>;

// neighbors[t][slot] = neighbour reference (index << 2 | type) or SM_NO_NEIGHBOR. Throws
// sm::Error naming `source`, the elements and (with `where`) a position when a face is shared by
// more than two elements or two elements are the same cell (duplicates would pair every face with
// their twin and vanish from the shell).
ConnectivityStats computeConnectivity(const ElementArrays& elements, uint64_t numVertices,
                                      ElementArrays& neighbors, const std::string& source,
                                      const VertexPosition& where = {});

}  // namespace sm::prep
