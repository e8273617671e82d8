// The readers behind readMesh (mesh_io.cpp chooses one by file name). They take the file's bytes
// so that fuzzers and in-memory callers can use them without files; `source` names the input in
// messages and, for .ugrid, gives the binary variant by its suffix.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "io/mesh_io.h"
#include "io_core/file_bytes.h"

namespace sm::io {

// pieceCluster: every cell gets this cluster id and cell arrays are not consulted (.pvtu pieces).
mesh::UnstructuredMesh readVtu(FileBytes bytes, const std::string& source,
                               const ReadOptions& options,
                               std::optional<int32_t> pieceCluster = std::nullopt);
// How readPvtu gets the bytes of the index and of each piece: FileBytes::open, or an in-memory
// lookup for fuzzers (a .pvtu is several files, and a fuzzer must not read whatever a mutated
// Source attribute names on the machine).
using OpenFile = std::function<FileBytes(const std::string& path)>;
mesh::UnstructuredMesh readPvtu(const std::string& path, const ReadOptions& options,
                                const OpenFile& open = &FileBytes::open);
int countPvtuPieces(const std::string& path);
// Cells each piece of a .pvtu declares in its header.
std::vector<uint64_t> pvtuPieceCellCounts(const std::string& path);
// Points and cells a .vtu, or each piece of a .pvtu in options.pieces, declare in their headers
// (nothing else is read).
struct DeclaredSize {
  uint64_t points = 0, cells = 0;
  bool operator==(const DeclaredSize&) const = default;
};
std::vector<DeclaredSize> declaredSizes(const std::string& path, const ReadOptions& options);
// True for a file that names pieces read and welded together: a .pvtu, or a multiblock .vtm whose
// unstructured-grid data sets are its pieces (one cluster each, in document order).
bool isPieceIndex(const std::string& path);
// The piece files a .pvtu (or .vtm) names (paths resolved against its folder).
std::vector<std::string> pvtuPieceFiles(const std::string& path);
std::vector<std::string> pvtuPieceFiles(const std::string& path, const OpenFile& open);
mesh::UnstructuredMesh readLegacyVtk(FileBytes bytes, const std::string& source,
                                     const ReadOptions& options);
// sideFiles: look for per-vertex field files beside `source` (docs/FORMATS.md); off for memory.
mesh::UnstructuredMesh readUgrid(FileBytes bytes, const std::string& source,
                                 const ReadOptions& options, bool sideFiles);

// Step `step` of point field `field` of a file read whole (.vtk, .ugrid), mapped by `pointMap`
// as readFieldStep maps it. `check`, when given, sees the mesh first: a series compares it with
// step 0's, so that a streamed step is parsed once for both.
std::vector<float> wholeReadFieldStep(
    const std::string& path, const std::string& field, uint64_t step, const ReadOptions& options,
    std::span<const uint32_t> pointMap,
    const std::function<void(const mesh::UnstructuredMesh&)>& check = {});

}  // namespace sm::io
