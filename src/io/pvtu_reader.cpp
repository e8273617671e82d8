// .pvtu reader: each <Piece Source="..."> is a .vtu read on its own, its cells given the piece's
// index as cluster id; the pieces are then welded into one mesh (weld.h).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "common/error.h"
#include "common/file_util.h"
#include "common/progress.h"
#include "io/readers.h"
#include "io/vtu_document.h"
#include "io_core/weld.h"
#include "mesh/mesh_builder.h"

namespace sm::io {

std::vector<std::string> pvtuPieceFiles(const std::string& path) {
  return pvtuPieceFiles(path, &FileBytes::open);
}

namespace {

// The unstructured grids of a multiblock file (.vtm), in document order: each <DataSet> at any
// depth of <Block>s and <Piece>s whose file is a .vtu, or the pieces of a .pvtu it names. Other
// data sets (a solver's boundary patches as .vtp surfaces, images) hold no volume to render and
// are left out; a <DataSet> with no file is an empty block.
std::vector<std::string> vtmPieceFiles(const std::string& path, const OpenFile& open) {
  FileBytes bytes = open(path);
  VtuDocument doc(bytes, path, "vtkMultiBlockDataSet");
  pugi::xml_node root = doc.root().child("vtkMultiBlockDataSet");
  if (!root) throw FileError(path, "has no <vtkMultiBlockDataSet> element");
  std::vector<std::string> files;
  for (pugi::xpath_node set : root.select_nodes(".//DataSet")) {
    const std::string file = set.node().attribute("file").value();
    const std::string resolved = joinPath(directoryOf(path), file);
    const std::string ext = fileExtension(file);
    if (ext == ".vtu") {
      files.push_back(resolved);
    } else if (ext == ".pvtu") {
      for (std::string& piece : pvtuPieceFiles(resolved, open)) files.push_back(std::move(piece));
    } else if (ext == ".vtm") {
      throw FileError(path, resolved == path ? "names itself" : "names another multiblock file",
                      " ('", file, "'); nest its blocks instead");
    }
  }
  if (files.empty())
    throw FileError(path, "holds no unstructured grid (.vtu or .pvtu data sets) to render");
  return files;
}

}  // namespace

bool isPieceIndex(const std::string& path) {
  const std::string ext = fileExtension(path);
  return ext == ".pvtu" || ext == ".vtm";
}

std::vector<std::string> pvtuPieceFiles(const std::string& path, const OpenFile& open) {
  if (fileExtension(path) == ".vtm") {
    std::vector<std::string> files = vtmPieceFiles(path, open);
    if (files.size() > 0x7FFFFFFF) throw FileError(path, "names too many pieces");
    return files;
  }
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

int countPvtuPieces(const std::string& path) {
  return static_cast<int>(pvtuPieceFiles(path).size());
}

namespace {

// The unsigned number in attribute `key` of one tag's text (`<Piece NumberOfPoints="8" ...`; XML
// allows spaces around '=' and either quote).
uint64_t tagNumber(const std::string& file, std::string_view tag, std::string_view key) {
  auto space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  for (size_t a = tag.find(key); a != std::string_view::npos; a = tag.find(key, a + 1)) {
    if (a == 0 || !space(tag[a - 1])) continue;
    size_t at = a + key.size();
    while (at < tag.size() && space(tag[at])) ++at;
    if (at >= tag.size() || tag[at] != '=') continue;
    ++at;
    while (at < tag.size() && space(tag[at])) ++at;
    if (at >= tag.size() || (tag[at] != '"' && tag[at] != '\'')) continue;
    const char quote = tag[at++];
    uint64_t n = 0;
    auto [end, ec] = std::from_chars(tag.data() + at, tag.data() + tag.size(), n);
    if (ec != std::errc() || end == tag.data() + tag.size() || *end != quote)
      throw FileError(file, "<Piece> attribute ", key, " is not a number");
    return n;
  }
  throw FileError(file, "a <Piece> has no ", key);
}

uint64_t addCapped(uint64_t a, uint64_t b) {
  return b > UINT64_MAX - a ? UINT64_MAX : a + b;
}

// NumberOfPoints and NumberOfCells of a .vtu, summed over its <Piece>s, from the start of the file
// only: the XML header precedes appended data, so a piece is sized without being read. The prefix
// read doubles until the header is complete (appended data or the grid's end seen, no tag cut
// off), so long field data before the <Piece> or an inline first piece only cost more reading;
// none (nullopt) once the prefix would pass `limit` bytes.
std::optional<DeclaredSize> declaredVtuSize(const std::string& file, size_t limit) {
  for (size_t prefix = size_t(1) << 12;; prefix *= 2) {
    const std::string head = FileBytes::readPrefix(file, prefix);
    checkPieceIsNotAnIndex({reinterpret_cast<const uint8_t*>(head.data()), head.size()}, file);
    const bool whole = head.size() < prefix;
    const size_t end = std::min(head.find("<AppendedData"), head.find("</UnstructuredGrid"));
    DeclaredSize size;
    bool found = false, cut = false;
    for (size_t at = head.find("<Piece"); at < end; at = head.find("<Piece", at + 6)) {
      const size_t close = head.find('>', at);
      if (close == std::string::npos) {
        cut = true;
        break;
      }
      const std::string_view tag(head.data() + at, close - at);
      size.points = addCapped(size.points, tagNumber(file, tag, "NumberOfPoints"));
      size.cells = addCapped(size.cells, tagNumber(file, tag, "NumberOfCells"));
      found = true;
    }
    if (!cut && (end != std::string::npos || whole)) {
      if (!found) throw FileError(file, "no <Piece NumberOfCells=...> in its header");
      return size;
    }
    if (whole) throw FileError(file, "its header ends inside a <Piece> tag");
    if (prefix >= limit) return std::nullopt;
  }
}

DeclaredSize declaredVtuSize(const std::string& file) {
  return *declaredVtuSize(file, SIZE_MAX);
}

// The points of the pieces about to be read (and their cells, where origins are kept), from their
// headers: a share past what one mesh holds is refused before any piece is read, not by the weld
// once all are. A header not found near the start of its file (an inline piece) is not read
// through for this, and one that cannot be read is left to the piece's reader to name: the weld
// checks again.
void checkDeclaredTotals(const std::string& path, const std::vector<std::string>& files,
                         const std::vector<int>& chosen, const ReadOptions& options) {
  constexpr size_t kHeaderBytes = size_t(1) << 20;
  DeclaredSize total;
  for (int i : chosen) {
    std::optional<DeclaredSize> size;
    try {
      size = declaredVtuSize(files[size_t(i)], kHeaderBytes);
    } catch (const Error&) {
      return;
    }
    if (!size) return;
    total.points = addCapped(total.points, size->points);
    total.cells = addCapped(total.cells, size->cells);
  }
  mesh::checkPointCount(path, total.points, "the pieces to be read declare", "use more ranks");
  if (options.cellOrigins && total.cells > 0xFFFFFFFFull)
    throw FileError(path, "the pieces to be read declare ", total.cells,
                    " cells: cell origins are 32-bit, so at most ", 0xFFFFFFFFull,
                    " can be kept (use more ranks)");
}

}  // namespace

std::vector<uint64_t> pvtuPieceCellCounts(const std::string& path) {
  std::vector<uint64_t> counts;
  for (const std::string& file : pvtuPieceFiles(path))
    counts.push_back(declaredVtuSize(file).cells);
  return counts;
}

std::vector<DeclaredSize> declaredSizes(const std::string& path, const ReadOptions& options) {
  if (fileExtension(path) == ".vtu") return {declaredVtuSize(path)};
  const std::vector<std::string> files = pvtuPieceFiles(path);
  std::vector<DeclaredSize> sizes;
  for (int i : choosePieces(path, files.size(), options))
    sizes.push_back(declaredVtuSize(files[i]));
  return sizes;
}

mesh::UnstructuredMesh readPvtu(const std::string& path, const ReadOptions& options,
                                const OpenFile& open) {
  // Refused rather than ignored: a user naming an array expects it to be used.
  if (!options.clusterArray.empty())
    throw FileError(path, "its pieces are its clusters; a cluster array ('", options.clusterArray,
                    "') is read from .vtu and .vtk files only");
  const std::vector<std::string> files = pvtuPieceFiles(path, open);
  std::vector<mesh::UnstructuredMesh> pieces;
  const std::vector<int> chosen = choosePieces(path, files.size(), options);
  // (Headers are read from files: an in-memory bundle, a fuzzer's, is checked by the weld only.)
  const bool fromFiles = open.target<FileBytes (*)(const std::string&)>() != nullptr;
  if (fromFiles) checkDeclaredTotals(path, files, chosen, options);
  Progress progress("piece read", chosen.size());
  for (int i : chosen) {
    pieces.push_back(readVtu(open(files[i]), files[i], options, i));
    progress.advance();
  }
  // From the pieces' headers: their fields' step counts (pieces loaded with one step each cannot
  // show the weld that they differ) and components (a magnitude welds to a scalar without a
  // seam), each piece against the file's first, so that ranks reading other pieces agree.
  if (options.loadFields && files.size() > 1 && (options.step || fromFiles))
    listFieldSteps(path, options);
  throwIfStopped(options.stopRequested, path);
  return weldPieces(path, std::move(pieces));
}

}  // namespace sm::io
