// .pvtu reader: each <Piece Source="..."> is a .vtu read on its own, its cells given the piece's
// index as cluster id; the pieces are then welded into one mesh (weld.h).
#include <algorithm>

#include "common/error.h"
#include "common/file_util.h"
#include "io/readers.h"
#include "io/vtu_document.h"
#include "io/weld.h"

namespace sm::io {
namespace {

std::vector<std::string> pieceFiles(const std::string& path) {
  FileBytes bytes = FileBytes::open(path);
  VtuDocument doc(bytes, path, "PUnstructuredGrid");
  pugi::xml_node grid = doc.root().child("PUnstructuredGrid");
  if (!grid) throw FileError(path, "has no <PUnstructuredGrid> element");
  std::vector<std::string> files;
  for (pugi::xml_node piece : grid.children("Piece")) {
    std::string_view src = piece.attribute("Source").value();
    if (src.empty()) throw FileError(path, "piece ", files.size(), " has no Source");
    files.push_back(joinPath(directoryOf(path), std::string(src)));  // relative to the .pvtu
  }
  if (files.empty()) throw FileError(path, "names no pieces");
  if (files.size() > 0x7FFFFFFF) throw FileError(path, "names too many pieces");
  return files;
}

std::vector<int> chosenPieces(const std::string& path, int count, const ReadOptions& options) {
  std::vector<int> chosen = options.pieces;
  if (chosen.empty()) {
    for (int i = 0; i < count; ++i) chosen.push_back(i);
    return chosen;
  }
  std::sort(chosen.begin(), chosen.end());
  for (size_t i = 0; i < chosen.size(); ++i) {
    if (chosen[i] < 0 || chosen[i] >= count)
      throw FileError(path, "has no piece ", chosen[i], " (pieces 0 to ", count - 1, ")");
    if (i > 0 && chosen[i] == chosen[i - 1])
      throw FileError(path, "piece ", chosen[i], " asked for twice");
  }
  return chosen;
}

}  // namespace

int countPvtuPieces(const std::string& path) {
  return static_cast<int>(pieceFiles(path).size());
}

mesh::UnstructuredMesh readPvtu(const std::string& path, const ReadOptions& options) {
  const std::vector<std::string> files = pieceFiles(path);
  std::vector<mesh::UnstructuredMesh> pieces;
  for (int i : chosenPieces(path, static_cast<int>(files.size()), options))
    pieces.push_back(readVtu(FileBytes::open(files[i]), files[i], options, i));
  return weldPieces(path, std::move(pieces));
}

}  // namespace sm::io
