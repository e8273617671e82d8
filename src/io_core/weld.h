// Joining the pieces of one data set (.pvtu) into one mesh.
#pragma once

#include <string>
#include <vector>

#include "mesh/unstructured_mesh.h"

namespace sm::io {

// Concatenates `pieces` (in order) into one mesh and merges points of different pieces whose
// coordinates are bitwise equal, so that faces between pieces become interior faces sharing
// vertex ids. Points of one piece are never merged with each other (the piece's own topology is
// kept exactly). Every piece must have the same fields (name and step count); a merged point keeps
// the first piece's values and a warning counts points whose pieces disagree. Cluster ids, skipped
// and fixed-cell counts carry over; time values come from the first piece that has them. The
// result's pointOrigin says where each of its points came from.
mesh::UnstructuredMesh weldPieces(const std::string& source,
                                  std::vector<mesh::UnstructuredMesh> pieces);

}  // namespace sm::io
