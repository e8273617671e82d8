// From the caller's arrays to the renderer's own mesh: checks what a simulation can get wrong
// (sizes, ids, coordinates) with messages in the API's terms, then hands the cells to
// mesh::MeshBuilder, the one place where cells enter a mesh (orientation, repeated vertices).
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/unstructured_mesh.h"
#include "shellmarch/insitu.h"

namespace sm::insitu {

// This rank's mesh as a copy; throws sm::Error on bad input. With polyhedra, the mesh's
// cellOrigin gives each element's number among the caller's elements (the four types' in order,
// then the polyhedra), and fileCells their count; without, cellOrigin is empty (the identity).
mesh::UnstructuredMesh meshFromView(const shellmarch::insitu::MeshView& view);
// MeshView::globalIds as a copy (empty when not given); throws sm::Error for a wrong count or a
// negative id.
std::vector<uint64_t> globalIdsFromView(const shellmarch::insitu::MeshView& view);

}  // namespace sm::insitu
