#include "io/mesh_io.h"

#include <cmath>

#include "common/error.h"
#include "common/file_util.h"
#include "common/log.h"
#include "io/readers.h"

namespace sm::io {
namespace {

enum class Format { Vtu, Pvtu, LegacyVtk, Ugrid };

Format formatOf(const std::string& path) {
  const std::string ext = fileExtension(path);
  if (ext == ".vtu") return Format::Vtu;
  if (ext == ".pvtu") return Format::Pvtu;
  if (ext == ".vtk") return Format::LegacyVtk;
  if (ext == ".ugrid") return Format::Ugrid;
  throw Error(path, ": unknown mesh format '", ext,
              "' (shellmarch reads .vtu, .pvtu, legacy .vtk and .ugrid files)");
}

// Ignoring a choice of pieces would load the whole file where the caller asked for part of it.
void checkNoPieces(const std::string& name, const ReadOptions& options) {
  if (!options.pieces.empty())
    throw FileError(name, "has no pieces to choose from (only a .pvtu has pieces)");
}

// Cell data asked for as fields becomes point data once every piece read is joined, so that
// points between pieces average the cells of both; with `average` false it is left to the caller
// (ranks that read some pieces each average with each other's help).
mesh::UnstructuredMesh withCellDataOnPoints(mesh::UnstructuredMesh m, bool average = true) {
  for (const mesh::CellField& f : m.cellFields) {
    log::info(m.source, ": field '", f.name,
              "' is cell data: each point takes the mean of the cells around it");
    uint64_t nonFinite = 0;
    for (const auto& step : f.steps)
      for (const auto& values : step)
        for (float v : values) nonFinite += !std::isfinite(v);
    if (nonFinite)
      log::warning(m.source, ": cell data '", f.name, "' has ", nonFinite,
                   " non-finite values; the points of those cells render transparent");
  }
  if (average) mesh::cellFieldsToPoints(m);
  return m;
}

mesh::UnstructuredMesh readAnyMesh(const std::string& path, const ReadOptions& options) {
  const Format format = formatOf(path);
  if (format != Format::Pvtu) checkNoPieces(path, options);
  switch (format) {
    case Format::Vtu:
      return readVtu(FileBytes::open(path), path, options);
    case Format::Pvtu:
      return readPvtu(path, options);
    case Format::LegacyVtk:
      return readLegacyVtk(FileBytes::open(path), path, options);
    case Format::Ugrid:
      return readUgrid(FileBytes::open(path), path, options, true);
  }
  return {};
}

}  // namespace

mesh::UnstructuredMesh readMesh(const std::string& path, const ReadOptions& options) {
  return withCellDataOnPoints(readAnyMesh(path, options), options.cellDataOnPoints);
}

mesh::UnstructuredMesh readMeshFromMemory(std::span<const uint8_t> bytes, const std::string& name,
                                          const ReadOptions& options) {
  const Format format = formatOf(name);
  if (format != Format::Pvtu) checkNoPieces(name, options);  // a .pvtu is refused below
  switch (format) {
    case Format::Vtu:
      return withCellDataOnPoints(readVtu(FileBytes::copyOf(bytes), name, options),
                                  options.cellDataOnPoints);
    case Format::Pvtu:
      throw Error(name, ": a .pvtu names its pieces by file; read it with readMesh");
    case Format::LegacyVtk:
      return withCellDataOnPoints(readLegacyVtk(FileBytes::copyOf(bytes), name, options),
                                  options.cellDataOnPoints);
    case Format::Ugrid:
      return readUgrid(FileBytes::copyOf(bytes), name, options, false);
  }
  return {};
}

int countPieces(const std::string& path) {
  return formatOf(path) == Format::Pvtu ? countPvtuPieces(path) : 1;
}

std::vector<std::string> meshFiles(const std::string& path) {
  std::vector<std::string> files{path};
  if (formatOf(path) == Format::Pvtu)
    for (std::string& piece : pvtuPieceFiles(path)) files.push_back(std::move(piece));
  return files;
}

std::string formatDescription(const std::string& path) {
  switch (formatOf(path)) {
    case Format::Vtu:
      return "VTK XML unstructured grid (.vtu)";
    case Format::Pvtu:
      return "parallel VTK XML unstructured grid (.pvtu)";
    case Format::LegacyVtk:
      return "legacy VTK unstructured grid (.vtk)";
    case Format::Ugrid:
      return "AFLR3/FUN3D UGRID (.ugrid)";
  }
  return {};
}

}  // namespace sm::io
