// .pvtu reader: each <Piece Source="..."> is a .vtu read on its own, its cells given the piece's
// index as cluster id; the pieces are then welded into one mesh (weld.h).
#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "common/error.h"
#include "common/file_util.h"
#include "io/readers.h"
#include "io/vtu_document.h"
#include "io/weld.h"

namespace sm::io {

std::vector<std::string> pvtuPieceFiles(const std::string& path) {
  return pvtuPieceFiles(path, &FileBytes::open);
}

std::vector<std::string> pvtuPieceFiles(const std::string& path, const OpenFile& open) {
  FileBytes bytes = open(path);
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

std::vector<int> pvtuChosenPieces(const std::string& path, int count, const ReadOptions& options) {
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

int countPvtuPieces(const std::string& path) {
  return static_cast<int>(pvtuPieceFiles(path).size());
}

namespace {

// NumberOfPoints and NumberOfCells of the <Piece> elements in the first bytes of a .vtu: the XML
// header precedes appended data, so a rank can size a piece without reading it.
DeclaredSize declaredVtuSize(const std::string& file, size_t prefix = 1 << 12) {
  const std::string head = FileBytes::readPrefix(file, prefix);
  checkPieceIsNotAnIndex({reinterpret_cast<const uint8_t*>(head.data()), head.size()}, file);
  DeclaredSize size;
  bool found = false;
  auto number = [&](size_t at, size_t close, const char* key) -> uint64_t {
    const std::string attr = std::string(key) + "=\"";
    size_t a = head.find(attr, at);
    if (a == std::string::npos || a > close) return 0;
    const char* first = head.c_str() + a + attr.size();
    char* end = nullptr;
    unsigned long long n = std::strtoull(first, &end, 10);
    if (end == first) throw FileError(file, key, " is not a number");
    return n;
  };
  for (size_t at = head.find("<Piece"); at != std::string::npos; at = head.find("<Piece", at + 6)) {
    const size_t close = head.find('>', at);
    if (head.find("NumberOfCells=\"", at) > close) continue;
    size.cells += number(at, close, "NumberOfCells");
    size.points += number(at, close, "NumberOfPoints");
    found = true;
  }
  // A series checks every step's header: 4 KiB hold the <Piece> tags of nearly every file.
  if (!found && prefix < (1 << 16) && head.size() == prefix) return declaredVtuSize(file, 1 << 16);
  if (!found) throw FileError(file, "no <Piece NumberOfCells=...> in its header");
  return size;
}

}  // namespace

std::vector<uint64_t> pvtuPieceCellCounts(const std::string& path) {
  std::vector<uint64_t> counts;
  for (const std::string& file : pvtuPieceFiles(path))
    counts.push_back(declaredVtuSize(file).cells);
  return counts;
}

DeclaredSize declaredSize(const std::string& path, const ReadOptions& options) {
  if (fileExtension(path) == ".vtu") return declaredVtuSize(path);
  const std::vector<std::string> files = pvtuPieceFiles(path);
  DeclaredSize total;
  for (int i : pvtuChosenPieces(path, static_cast<int>(files.size()), options)) {
    const DeclaredSize piece = declaredVtuSize(files[i]);
    total.points += piece.points;
    total.cells += piece.cells;
  }
  return total;
}

mesh::UnstructuredMesh readPvtu(const std::string& path, const ReadOptions& options,
                                const OpenFile& open) {
  // Refused rather than ignored: a user naming an array expects it to be used.
  if (!options.clusterArray.empty())
    throw FileError(path, "its pieces are its clusters; a cluster array ('", options.clusterArray,
                    "') is read from .vtu and .vtk files only");
  const std::vector<std::string> files = pvtuPieceFiles(path, open);
  std::vector<mesh::UnstructuredMesh> pieces;
  for (int i : pvtuChosenPieces(path, static_cast<int>(files.size()), options))
    pieces.push_back(readVtu(open(files[i]), files[i], options, i));
  // Pieces loaded with one step each cannot show the weld that their step counts differ.
  if (options.step && options.loadFields && pieces.size() > 1) listFieldSteps(path, options);
  return weldPieces(path, std::move(pieces));
}

}  // namespace sm::io
