#include "io/mesh_io.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/file_util.h"
#include "common/log.h"
#include "io/readers.h"
#include "io/series.h"
#include "solver_io/pieced_readers.h"

namespace sm::io {
namespace {

enum class Format { Vtu, Pvtu, LegacyVtk, Ugrid, Series, Pieced };

Format formatOf(const std::string& path) {
  const std::string ext = fileExtension(path);
  if (ext == ".vtu") return Format::Vtu;
  if (isPieceIndex(path)) return Format::Pvtu;
  if (ext == ".vtk") return Format::LegacyVtk;
  if (ext == ".ugrid") return Format::Ugrid;
  if (isSeries(path)) return Format::Series;
  if (piecedFormatOf(path)) return Format::Pieced;
  throw Error(path, ": unknown mesh format '", ext,
              "' (shellmarch reads .vtu, .pvtu, .vtm, legacy .vtk, .ugrid, CGNS (.cgns), Exodus II "
              "(.e, .exo), SU2 (.su2) and Gmsh (.msh) files, and time series of VTK files as .pvd "
              "or .series files)");
}

// Ignoring a choice of pieces would load the whole file where the caller asked for part of it.
void checkNoPieces(const std::string& name, const ReadOptions& options) {
  if (!options.pieces.empty())
    throw FileError(
        name,
        "has no pieces to choose from (only a .pvtu or .vtm, or a series of them, has pieces)");
}

// Cell data asked for as fields becomes point data once every piece read is joined, so that
// points between pieces average the cells of both; with `average` false it is left to the caller
// (ranks that read some pieces each average with each other's help).
mesh::UnstructuredMesh withCellDataOnPoints(mesh::UnstructuredMesh m, bool average = true) {
  for (const mesh::CellField& f : m.cellFields) {
    log::info(m.source, ": field '", f.name,
              "' is cell data: each point takes the mean of the cells around it");
    // Counted by cells of the file: a polyhedron's tetrahedra once.
    const bool byOrigin = m.cellOrigin.size() == m.numCells();
    uint64_t nonFinite = 0, firstStep = 0;
    for (size_t k = 0; k < f.steps.size(); ++k) {
      size_t first = 0;
      for (const auto& values : f.steps[k]) {
        const uint64_t n = mesh::nonFiniteCells(
            values, byOrigin ? std::span(m.cellOrigin).subspan(first, values.size())
                             : std::span<const uint32_t>());
        if (n > 0 && nonFinite == 0) firstStep = k;
        nonFinite += n;
        first += values.size();
      }
    }
    // The step is named: a series' mesh is named after its first file, whichever holds them.
    if (nonFinite)
      log::warning(m.source, ": cell data '", f.name, "' has ", nonFinite,
                   " non-finite values (first in step ", firstStep,
                   "); the points of those cells render transparent");
  }
  if (average) mesh::cellFieldsToPoints(m);
  return m;
}

mesh::UnstructuredMesh readAnyMesh(const std::string& path, const ReadOptions& options) {
  const Format format = formatOf(path);
  if (format != Format::Pvtu && format != Format::Series && format != Format::Pieced)
    checkNoPieces(path, options);
  // One step of a file of many (a stream's first) touches a small part of it: its pages are mapped
  // as they are read instead of all up front.
  const OpenFile open = options.step ? &FileBytes::openLazily : &FileBytes::open;
  switch (format) {
    case Format::Vtu:
      return readVtu(open(path), path, options);
    case Format::Pvtu:
      return readPvtu(path, options, open);
    case Format::LegacyVtk:
      return readLegacyVtk(FileBytes::open(path), path, options);
    case Format::Ugrid:
      return readUgrid(FileBytes::open(path), path, options, true);
    case Format::Series:
      return readSeries(path, options, &readAnyMesh);
    case Format::Pieced:
      return readPieced(*piecedFormatOf(path), path, options);
  }
  return {};
}

// The file that stands for a series in questions about pieces and headers: its first step.
std::string firstFile(const std::string& path) {
  return isSeries(path) ? readSeriesIndex(path).at(0).file : path;
}

}  // namespace

mesh::UnstructuredMesh readMesh(const std::string& path, const ReadOptions& options) {
  throwIfStopped(options.stopRequested, path);
  return withCellDataOnPoints(readAnyMesh(path, options), options.cellDataOnPoints);
}

mesh::UnstructuredMesh readMeshFromMemory(std::span<const uint8_t> bytes, const std::string& name,
                                          const ReadOptions& options) {
  const Format format = formatOf(name);
  const std::optional<PiecedFormat> pieced = piecedFormatOf(name);
  // A .pvtu is refused below; the text formats with pieces choose them.
  if (format != Format::Pvtu && pieced != PiecedFormat::Su2 && pieced != PiecedFormat::Gmsh)
    checkNoPieces(name, options);
  switch (format) {
    case Format::Vtu:
      return withCellDataOnPoints(readVtu(FileBytes::copyOf(bytes), name, options),
                                  options.cellDataOnPoints);
    case Format::Pvtu:
      throw Error(name, ": a .pvtu or .vtm names its pieces by file; read it with readMesh");
    case Format::LegacyVtk:
      return withCellDataOnPoints(readLegacyVtk(FileBytes::copyOf(bytes), name, options),
                                  options.cellDataOnPoints);
    case Format::Ugrid:
      return readUgrid(FileBytes::copyOf(bytes), name, options, false);
    case Format::Series:
      throw Error(name, ": a series names its steps by file; read it with readMesh");
    case Format::Pieced:
      return withCellDataOnPoints(readPiecedBytes(*pieced, FileBytes::copyOf(bytes), name, options),
                                  options.cellDataOnPoints);
  }
  return {};
}

int countPieces(const std::string& path) {
  const std::string file = firstFile(path);
  if (const std::optional<PiecedFormat> f = piecedFormatOf(file))
    return static_cast<int>(piecedLayout(*f, file).pieces.size());
  return formatOf(file) == Format::Pvtu ? countPvtuPieces(file) : 1;
}

bool readsByPiece(const std::string& path) {
  const std::string file = firstFile(path);
  // One piece is read whole, so that it can be split among ranks after reading.
  if (piecedFormatOf(file)) return countPieces(file) > 1;
  return formatOf(file) == Format::Pvtu;
}

bool readsStepsAlone(const std::string& path) {
  const Format f = formatOf(firstFile(path));
  return f == Format::Vtu || f == Format::Pvtu;
}

bool listsFieldsFromHeaders(const std::string& path) {
  return readsStepsAlone(path) || piecedFormatOf(firstFile(path));
}

std::vector<std::string> pieceFiles(const std::string& path) {
  const std::string file = firstFile(path);
  if (const std::optional<PiecedFormat> f = piecedFormatOf(file))
    return piecedLayout(*f, file).pieces;
  return formatOf(file) == Format::Pvtu ? pvtuPieceFiles(file) : std::vector<std::string>{file};
}

std::vector<uint64_t> pieceCellCounts(const std::string& path) {
  const std::string file = firstFile(path);
  if (const std::optional<PiecedFormat> f = piecedFormatOf(file))
    return piecedLayout(*f, file).pieceCells;
  if (formatOf(file) != Format::Pvtu)
    throw FileError(path, "has no pieces (only a .pvtu, or a series of them, has pieces)");
  return pvtuPieceCellCounts(file);
}

std::vector<std::string> meshFiles(const std::string& path) {
  if (const std::optional<PiecedFormat> f = piecedFormatOf(path)) {
    std::vector<std::string> files = piecedLayout(*f, path).files;
    if (std::find(files.begin(), files.end(), path) == files.end())
      files.insert(files.begin(), path);
    return files;
  }
  std::vector<std::string> files{path};
  if (formatOf(path) == Format::Series) {
    for (const SeriesStep& s : readSeriesIndex(path))
      for (std::string& f : meshFiles(s.file)) files.push_back(std::move(f));
  } else if (formatOf(path) == Format::Pvtu) {
    for (std::string& piece : pvtuPieceFiles(path)) files.push_back(std::move(piece));
  }
  return files;
}

std::string formatDescription(const std::string& path) {
  switch (formatOf(path)) {
    case Format::Vtu:
      return "VTK XML unstructured grid (.vtu)";
    case Format::Pvtu:
      return fileExtension(path) == ".vtm" ? "VTK XML multiblock (.vtm) of unstructured grids"
                                           : "parallel VTK XML unstructured grid (.pvtu)";
    case Format::LegacyVtk:
      return "legacy VTK unstructured grid (.vtk)";
    case Format::Ugrid:
      return "AFLR3/FUN3D UGRID (.ugrid)";
    case Format::Pieced:
      return piecedFormatDescription(*piecedFormatOf(path));
    case Format::Series: {
      const std::vector<SeriesStep> steps = readSeriesIndex(path);
      return concat("time series (", fileExtension(path) == ".pvd" ? "ParaView .pvd" : ".series",
                    ") of ", steps.size(), " files, each a ", formatDescription(steps[0].file));
    }
  }
  return {};
}

}  // namespace sm::io
