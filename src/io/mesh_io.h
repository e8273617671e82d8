// Reading and writing meshes. Format is chosen by file extension:
//   .vtu   VTK XML unstructured grid (ascii, inline base64, appended raw/base64, zlib)
//   .pvtu  parallel VTK XML: one piece = one cluster; pieces of one read are welded (exactly
//          coincident points merged) so that faces between clusters become interior
//   .vtm   VTK XML multiblock: its unstructured-grid data sets are read as a .pvtu's pieces
//   .vtk   legacy VTK UNSTRUCTURED_GRID, ascii or binary, versions 3 (CELLS/CELL_TYPES) and 5.1
//          (OFFSETS/CONNECTIVITY)
//   .ugrid FUN3D/AFLR3 (.ugrid ascii; .b8/.lb8 binary, .b8l/.lb8l 64-bit ints, ...), fields from
//          float32 side files (docs/FORMATS.md)
//   .pvd, .series  time series of one mesh, a file per step (ParaView's data collection, or the
//          JSON file series NAME.vtu.series): the first file's mesh, each field's step k from the
//          k-th file in time order; options.pieces apply to every step's .pvtu
// Time steps in VTK XML files are point arrays named "NAME@t<K>" (K = 0, 1, ...), grouped into one
// field NAME with K steps; a plain "NAME" is a field with one step.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "io_core/read_options.h"
#include "mesh/unstructured_mesh.h"

namespace sm::io {

mesh::UnstructuredMesh readMesh(const std::string& path, const ReadOptions& options = {});

// Reads a mesh held in memory (fuzzers, in-situ callers); `name` gives the format as a path does
// and names the input in messages. .pvtu is not accepted (its pieces are files), and .ugrid
// fields are not looked for (they live in side files).
mesh::UnstructuredMesh readMeshFromMemory(std::span<const uint8_t> bytes, const std::string& name,
                                          const ReadOptions& options = {});

// What readMesh takes the file for, in words ("VTK XML unstructured grid (.vtu)", ...); throws
// sm::Error for a name no reader accepts.
std::string formatDescription(const std::string& path);

// Pieces in a .pvtu, or a series of them, without reading them (1 for every other format).
int countPieces(const std::string& path);
// True for a .pvtu or a series of them: ranks can read some pieces each (ReadOptions::pieces).
bool readsByPiece(const std::string& path);
// True when readFieldStep reads a step without reading the whole file again (.vtu, .pvtu, and
// series of them): what streaming a time series needs.
bool readsStepsAlone(const std::string& path);
// True when listFieldSteps knows the fields from headers, without reading the file whole (.vtu,
// .pvtu, series of them, CGNS, Exodus II, SU2 and Gmsh files).
bool listsFieldsFromHeaders(const std::string& path);
// The files of the pieces of a .pvtu (or of a series' first step), for messages; else the file.
std::vector<std::string> pieceFiles(const std::string& path);

// The mesh files readMesh(path) reads: `path`, a .pvtu's pieces, a series' files and their
// pieces. (Outputs must not be one.)
std::vector<std::string> meshFiles(const std::string& path);

// Cells each piece of a .pvtu (or of a series' first step) declares in its header (the pieces are
// not read): what ranks need to share pieces out by element count before each reads only its own.
std::vector<uint64_t> pieceCellCounts(const std::string& path);

// The point fields readMesh(path, options) loads, with their step counts, without loading them:
// .vtu and .pvtu are read from their XML headers (a .pvtu's from the headers of the pieces in
// options.pieces, which must agree); legacy .vtk and .ugrid files are read whole.
std::vector<FieldStepCount> listFieldSteps(const std::string& path,
                                           const ReadOptions& options = {});

// True when options.fields names cell data that readMesh would average onto the points (a .vtu's
// or a .pvtu's first piece's header says; other formats are always read whole). Such a field is
// not streamed step by step, and a partitioned mesh must be read whole before it is split.
bool asksForCellData(const std::string& path, const ReadOptions& options);

// The cell data arrays a .vtu, a .pvtu's first piece or a series' first file holds (numeric, not
// bookkeeping or cluster ids; a vector once, by name), from its XML header; empty for other
// formats. What ReadOptions::fields may name as cell data.
std::vector<std::string> listCellData(const std::string& path, const ReadOptions& options = {});

// Step `step` of point field `field` ("NAME" or "NAME[k]", as ReadOptions::fields), read from the
// file without its points and cells: only that field's DataArray is decoded (.vtu, and the .vtu
// pieces in options.pieces of a .pvtu). Values come in the order of the points of the pieces
// read, numbered one after another; when `pointMap` is not empty, value i is the value of that
// point pointMap[i]. Pass the point origins of the mesh readMesh(path, options) returned
// (mesh.pointOrigin) to get that mesh's order: a .pvtu's welded points, or a .vtu's own points
// (pointOrigin empty). Legacy .vtk and .ugrid files are read whole (slow; the rest of the mesh is
// dropped). Throws sm::FileError naming the file and the array for a field or step that is not
// there and for damaged or truncated data.
std::vector<float> readFieldStep(const std::string& path, const std::string& field, uint64_t step,
                                 const ReadOptions& options = {},
                                 std::span<const uint32_t> pointMap = {});

// Step `step` of cell data `field` (as ReadOptions::fields names it), without the mesh: only that
// cell array is decoded, from .vtu and .pvtu files (the pieces in options.pieces) and series of
// them. Values come in the order of the cells of the pieces read, numbered one after another
// (skipped cells included); when `cellMap` is not empty, value i is that of cell cellMap[i]. Pass
// the cell origins of the mesh readMesh(path, options with cellOrigins) returned to get one value
// per element of that mesh, type by type. Throws sm::FileError naming the file and the array for a
// field or step that is not there, a field held as point data, and damaged or truncated data.
std::vector<float> readCellFieldStep(const std::string& path, const std::string& field,
                                     uint64_t step, const ReadOptions& options = {},
                                     std::span<const uint32_t> cellMap = {});

struct WriteOptions {
  bool compress = true;  // zlib-compressed appended raw data
  unsigned threads = 0;  // threads compressing (0: all cores)
};

// Writes a .pvtu and one .vtu per cluster beside it (PATH_STEM/PATH_STEM_<k>.vtu). Fields with
// several time steps are written as NAME@t<K> arrays. The files are written to temporary names and
// renamed when complete.
void writePvtu(const std::string& path, const mesh::UnstructuredMesh& mesh,
               const WriteOptions& options = {});
// Writes a .pvtu one piece at a time, so that a generator's memory is bounded by a piece, not
// the mesh: pieces go to staging names beside their final ones and are renamed into place, the
// index last, only by finish(); destroyed unfinished, it removes what it staged. `layout` gives
// the field names, their step counts and the time values (its geometry is not used); every piece
// must carry those fields. write() may run on several threads at once for different pieces.
class PvtuPieceWriter {
 public:
  PvtuPieceWriter(const std::string& path, uint64_t pieces, const mesh::UnstructuredMesh& layout,
                  const WriteOptions& options = {});
  ~PvtuPieceWriter();
  PvtuPieceWriter(const PvtuPieceWriter&) = delete;
  PvtuPieceWriter& operator=(const PvtuPieceWriter&) = delete;
  void write(uint64_t piece, const mesh::UnstructuredMesh& mesh);
  void finish();

 private:
  std::string pieceFileName(uint64_t piece) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Writes a time series: PATH_STEM/PATH_STEM_t<K>.pvtu for each step K (every field at step K, or
// its last), and the .pvd at `path` naming them with mesh.timeValues (or K when there are none),
// written last. readMesh(path) reads it back as the same fields and steps.
void writePvdSeries(const std::string& path, const mesh::UnstructuredMesh& mesh,
                    const WriteOptions& options = {});
// Writes one .vtu (appended raw, optional zlib) with the cluster ids as a cell array "cluster".
void writeVtu(const std::string& path, const mesh::UnstructuredMesh& mesh,
              const WriteOptions& options = {});

}  // namespace sm::io
