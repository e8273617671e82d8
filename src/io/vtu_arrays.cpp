#include "io/vtu_arrays.h"

#include <string>

#include "common/error.h"
#include "mesh/mesh_builder.h"

namespace sm::io {

std::vector<VtuPiece> vtuPieces(const VtuDocument& doc) {
  const std::string& src = doc.source();
  pugi::xml_node grid = doc.root().child("UnstructuredGrid");
  if (!grid) throw FileError(src, "has no <UnstructuredGrid> element");
  std::vector<VtuPiece> pieces;
  uint64_t points = 0, cells = 0;
  for (pugi::xml_node p : grid.children("Piece")) {
    VtuPiece piece{p, doc.count(p, "NumberOfPoints"), doc.count(p, "NumberOfCells"), points, cells};
    points += piece.numPoints;
    cells += piece.numCells;
    pieces.push_back(piece);
    // Before anything is read, and before the sum can wrap (each count is at most 2^60).
    mesh::checkPointCount(src, points, pieces.size() > 1 ? "its pieces declare" : "declares",
                          "split it into the pieces of a .pvtu and use more ranks");
    if (cells > uint64_t(1) << 60)  // as VtuDocument::count bounds one piece's
      throw FileError(src, "its pieces declare ", cells, " cells, more than a file can hold");
  }
  if (pieces.empty()) throw FileError(src, "has no <Piece> element");
  return pieces;
}

pugi::xml_node findDataArray(pugi::xml_node parent, std::string_view name) {
  for (pugi::xml_node a : parent.children("DataArray"))
    if (name == a.attribute("Name").value()) return a;
  return {};
}

namespace {

std::vector<ArrayInfo> numericArrays(const VtuDocument& doc, pugi::xml_node data,
                                     const char* what) {
  std::string_view globalIds = data.attribute("GlobalIds").value();
  std::string_view pedigreeIds = data.attribute("PedigreeIds").value();
  std::vector<ArrayInfo> infos;
  for (pugi::xml_node a : data.children("DataArray")) {
    std::string_view name = a.attribute("Name").value();
    if (!scalarTypeFromXml(a.attribute("type").value())) continue;  // strings and the like
    bool id = name == globalIds || name == pedigreeIds || isBookkeepingArray(name);
    infos.push_back({std::string(name), doc.components(a, concat(what, " '", name, "'")), id});
  }
  return infos;
}

}  // namespace

std::vector<ArrayInfo> vtuPointArrays(const VtuDocument& doc, const VtuPiece& piece) {
  return numericArrays(doc, piece.node.child("PointData"), "point array");
}

std::vector<ArrayInfo> vtuCellArrays(const VtuDocument& doc, const VtuPiece& piece) {
  return numericArrays(doc, piece.node.child("CellData"), "cell array");
}

std::vector<std::string> vtuCellArrayNames(const VtuPiece& piece) {
  std::vector<std::string> names;
  for (pugi::xml_node a : piece.node.child("CellData").children("DataArray"))
    names.emplace_back(a.attribute("Name").value());
  return names;
}

}  // namespace sm::io
