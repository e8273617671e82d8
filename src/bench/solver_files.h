// The benchmark's copies of one mesh in the solvers' formats, written through the formats' own
// libraries (libcgns, libexodusii), so that `bench prep --formats` reads the same mesh as .pvtu,
// CGNS and Exodus II side by side. Every cluster becomes one CGNS zone (its own points, as a
// partitioned solver writes them) or one Exodus element block per element type (shared nodes).
// Step 0 of every point field is written as a Vertex solution / nodal variable.
#pragma once

#include <string>

#include "mesh/unstructured_mesh.h"

namespace sm::app::bench {

void writeCgnsCopy(const std::string& path, const mesh::UnstructuredMesh& m);
void writeExodusCopy(const std::string& path, const mesh::UnstructuredMesh& m);

}  // namespace sm::app::bench
