// Connectivity by face matching (the paper's "Connectivity Generation"): one neighbour per
// element face, found by bucketing faces by their smallest vertex id (a counting sort) and
// matching equal vertex sets inside each bucket. O(faces) time, 4 bytes per face of scratch.
#pragma once

#include <string>

#include "prep/face_slots.h"

namespace sm::prep {

struct ConnectivityStats {
  uint64_t interiorFaces = 0;  // matched pairs
  uint64_t boundaryFaces = 0;  // faces with no neighbour on this rank (the shell)
};

// neighbors[t][slot] = neighbour reference (index << 2 | type) or SM_NO_NEIGHBOR. Throws
// sm::Error naming `source` and the elements when a face is shared by more than two elements.
ConnectivityStats computeConnectivity(const ElementArrays& elements, uint64_t numVertices,
                                      ElementArrays& neighbors, const std::string& source);

}  // namespace sm::prep
