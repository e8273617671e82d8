// Readers of the formats solvers write whose one file (or one set of files) holds several pieces:
// CGNS zones, Exodus II element blocks (or the files of a decomposed mesh), SU2 zones and Gmsh
// partitions. Piece i becomes cluster i, so that ranks can read some pieces each (ReadOptions::
// pieces) and the renderer has the solver's partitions; the pieces read are welded as a .pvtu's are
// (io_core/weld.h). Time steps are the file's own (solutions, time steps, $NodeData steps).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "io_core/file_bytes.h"
#include "io_core/read_options.h"
#include "mesh/unstructured_mesh.h"

namespace sm::io {

enum class PiecedFormat { Cgns, Exodus, Su2, Gmsh };

// The format a file name says (.cgns; .e .exo .ex2 .exii .g .gen and a decomposed Exodus mesh's
// NAME.e.N.i files; .su2; .msh), or none.
std::optional<PiecedFormat> piecedFormatOf(const std::string& path);
std::string piecedFormatDescription(PiecedFormat format);

// What a file holds, from its headers and sizes: no coordinates, connectivity or field values.
struct PiecedLayout {
  // Each piece's name for messages, with the file: "flow.cgns, zone 'blk1'".
  std::vector<std::string> pieces;
  // Volume cells each piece declares (cells the reader will skip may be counted; never fewer).
  std::vector<uint64_t> pieceCells;
  // Every field the file holds: point fields, and cell data (cellData set) which is read only when
  // ReadOptions::fields names it. A vector held as one array has its component count; formats that
  // store components as separate scalars (CGNS, Exodus) list each scalar.
  std::vector<FieldStepCount> fields;
  std::vector<double> times;       // time of each step, where the file says
  std::vector<std::string> files;  // every file read (a decomposed Exodus mesh: one per piece)
};

// Every reader: reads the pieces in options.pieces (all when empty; a number out of range is a
// sm::FileError), each as cluster `its index`; loads the fields options.fields names (point
// fields, and cell data named by name, which is left in mesh.cellFields for readMesh to average;
// empty: every point field, vectors as their magnitude, "NAME[k]" one component), only step
// options.step where set; asks options.stopRequested before each piece and step; throws
// sm::FileError naming the file and the place (zone, block, section, line) for anything truncated,
// corrupt or inconsistent. Cells that are not volume cells are counted as skipped (SkippedCells).
PiecedLayout cgnsLayout(const std::string& path);
mesh::UnstructuredMesh readCgns(const std::string& path, const ReadOptions& options);

PiecedLayout exodusLayout(const std::string& path);
mesh::UnstructuredMesh readExodus(const std::string& path, const ReadOptions& options);

// Text formats take the bytes, so that fuzzers read them without files.
PiecedLayout su2Layout(const FileBytes& bytes, const std::string& source);
mesh::UnstructuredMesh readSu2(const FileBytes& bytes, const std::string& source,
                               const ReadOptions& options);

PiecedLayout gmshLayout(const FileBytes& bytes, const std::string& source);
mesh::UnstructuredMesh readGmsh(const FileBytes& bytes, const std::string& source,
                                const ReadOptions& options);

// Dispatch by format (the text formats open the file).
PiecedLayout piecedLayout(PiecedFormat format, const std::string& path);
mesh::UnstructuredMesh readPieced(PiecedFormat format, const std::string& path,
                                  const ReadOptions& options);

// Step `step` of point field `field` of the pieces in options.pieces, in the order of the points
// of the mesh readPieced(format, path, options) returns (the pieces are read again, with only that
// step of that field).
std::vector<float> piecedFieldStep(PiecedFormat format, const std::string& path,
                                   const std::string& field, uint64_t step,
                                   const ReadOptions& options);

// readPieced of a text format's bytes (fuzzers, in-memory callers); CGNS and Exodus II files are
// refused (their libraries open files).
mesh::UnstructuredMesh readPiecedBytes(PiecedFormat format, const FileBytes& bytes,
                                       const std::string& name, const ReadOptions& options);

// The fields readPieced(format, path, options) loads, with their steps, from the layout.
std::vector<FieldStepCount> piecedFieldSteps(const std::string& path, const PiecedLayout& layout,
                                             const ReadOptions& options);

}  // namespace sm::io
