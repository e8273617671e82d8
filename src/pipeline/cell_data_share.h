// Cell data read piece by piece on several ranks, averaged onto the points as if one process had
// read the whole mesh (mesh::cellFieldsToPoints), without any rank reading the whole mesh.
#pragma once

#include <string>

#include "comm/reductions.h"
#include "mesh/unstructured_mesh.h"

namespace sm::app {

// Averages the cell fields of a rank's share (read with io::ReadOptions::cellDataOnPoints false)
// onto its points, the cells of every rank counted: for conforming pieces that do not overlap, the
// result equals what mesh::cellFieldsToPoints gives the welded whole, up to the order of
// summation. Collective; `holdsPieces` false for a rank that read no pieces (it takes part with an
// empty mesh); `pieces` names this rank's pieces in messages. Throws sm::Error on every rank when
// ranks holding pieces disagree about the cell fields' names or step counts.
void cellDataToPointsOverRanks(mesh::UnstructuredMesh& m, bool holdsPieces,
                               const std::string& pieces, comm::Communicator& comm);

}  // namespace sm::app
