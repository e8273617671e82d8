// What a .vtu holds, read from its XML structure alone: its pieces and their point arrays. Shared
// by the mesh reader and the one-step field reader, so that both pick arrays by the same rules.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include <pugixml.hpp>

#include "io/vtu_document.h"
#include "io_core/array_plan.h"

namespace sm::io {

struct VtuPiece {
  pugi::xml_node node;
  uint64_t numPoints = 0, numCells = 0;
  uint64_t firstPoint = 0, firstCell = 0;  // in the whole file
};

// The <Piece>s of the document's <UnstructuredGrid>; sm::FileError when there are none.
std::vector<VtuPiece> vtuPieces(const VtuDocument& doc);

// The DataArray child named `name`, or an empty node.
pugi::xml_node findDataArray(pugi::xml_node parent, std::string_view name);

// The numeric point arrays of a piece (string arrays are left out); ids and bookkeeping arrays
// are marked as identifiers.
std::vector<ArrayInfo> vtuPointArrays(const VtuDocument& doc, const VtuPiece& piece);

// The same for its cell arrays.
std::vector<ArrayInfo> vtuCellArrays(const VtuDocument& doc, const VtuPiece& piece);

// The names of a piece's cell arrays, in file order.
std::vector<std::string> vtuCellArrayNames(const VtuPiece& piece);

}  // namespace sm::io
