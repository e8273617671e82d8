#include "solver_io/pieced_readers.h"

#include <algorithm>
#include <filesystem>
#include <mutex>
#include <regex>

#include "common/error.h"
#include "common/file_util.h"
#include "io_core/array_plan.h"

namespace sm::io {
namespace {

// A decomposed Exodus mesh (Nemesis, SEACAS decomp): NAME.e.N.i, i = 0 .. N-1.
bool isDecomposedExodusName(const std::string& path) {
  static const std::regex pattern(R"(.*\.(e|exo|ex2|exii|g|gen)\.[0-9]+\.[0-9]+$)",
                                  std::regex::icase);
  return std::regex_match(path, pattern);
}

std::string fieldNames(const PiecedLayout& layout) {
  std::string names;
  for (const FieldStepCount& f : layout.fields)
    names += concat(names.empty() ? "" : ", ", "'", f.name, "'", f.cellData ? " (cell data)" : "");
  return names.empty() ? "none" : names;
}

const FieldStepCount* findField(const PiecedLayout& layout, const std::string& name,
                                bool cellData) {
  for (const FieldStepCount& f : layout.fields)
    if (f.name == name && f.cellData == cellData) return &f;
  return nullptr;
}

}  // namespace

std::optional<PiecedFormat> piecedFormatOf(const std::string& path) {
  const std::string ext = fileExtension(path);
  if (ext == ".cgns") return PiecedFormat::Cgns;
  if (ext == ".e" || ext == ".exo" || ext == ".ex2" || ext == ".exii" || ext == ".g" ||
      ext == ".gen" || isDecomposedExodusName(path))
    return PiecedFormat::Exodus;
  if (ext == ".su2") return PiecedFormat::Su2;
  if (ext == ".msh") return PiecedFormat::Gmsh;
  return std::nullopt;
}

std::string piecedFormatDescription(PiecedFormat format) {
  switch (format) {
    case PiecedFormat::Cgns:
      return "CGNS (.cgns)";
    case PiecedFormat::Exodus:
      return "Exodus II (.e, .exo)";
    case PiecedFormat::Su2:
      return "SU2 native mesh (.su2)";
    case PiecedFormat::Gmsh:
      return "Gmsh mesh (.msh)";
  }
  return {};
}

namespace {

PiecedLayout readLayout(PiecedFormat format, const std::string& path) {
  switch (format) {
    case PiecedFormat::Cgns:
      return cgnsLayout(path);
    case PiecedFormat::Exodus:
      return exodusLayout(path);
    case PiecedFormat::Su2:
      return su2Layout(FileBytes::open(path), path);
    case PiecedFormat::Gmsh:
      return gmshLayout(FileBytes::open(path), path);
  }
  return {};
}

// The file's identity for the layout kept below: a file rewritten in place is scanned again.
struct FileStamp {
  std::string path;
  std::filesystem::file_time_type modified;
  uintmax_t size = 0;
  bool operator==(const FileStamp&) const = default;
};

std::optional<FileStamp> stampOf(const std::string& path) {
  std::error_code ec;
  FileStamp s{path, std::filesystem::last_write_time(path, ec), 0};
  if (!ec) s.size = std::filesystem::file_size(path, ec);
  if (ec) return std::nullopt;
  return s;
}

}  // namespace

PiecedLayout piecedLayout(PiecedFormat format, const std::string& path) {
  // Ranks ask for the layout several times before and around one read (pieces, their sizes,
  // fields, cell data), and a text format's layout is a scan of the whole file: the last one is
  // kept.
  static std::mutex mutex;
  static std::optional<std::pair<FileStamp, PiecedLayout>> last;
  const std::optional<FileStamp> stamp = stampOf(path);
  {
    std::lock_guard lock(mutex);
    if (stamp && last && last->first == *stamp) return last->second;
  }
  PiecedLayout layout = readLayout(format, path);
  if (stamp) {
    std::lock_guard lock(mutex);
    last.emplace(*stamp, layout);
  }
  return layout;
}

namespace {

void checkNoClusterArray(const std::string& name, const ReadOptions& options) {
  if (!options.clusterArray.empty())
    throw FileError(name,
                    "its pieces (zones, blocks, partitions) are its clusters; a cluster array ('",
                    options.clusterArray, "') is read from .vtu and .vtk files only");
}

// A later step is read by reading the same pieces again (piecedFieldStep), which gives the welded
// points themselves: a map back to the pieces' own points would be applied to values that are
// already welded.
mesh::UnstructuredMesh withoutPointOrigins(mesh::UnstructuredMesh m) {
  m.pointOrigin.clear();
  return m;
}

}  // namespace

mesh::UnstructuredMesh readPieced(PiecedFormat format, const std::string& path,
                                  const ReadOptions& options) {
  checkNoClusterArray(path, options);
  switch (format) {
    case PiecedFormat::Cgns:
      return withoutPointOrigins(readCgns(path, options));
    case PiecedFormat::Exodus:
      return withoutPointOrigins(readExodus(path, options));
    case PiecedFormat::Su2:
    case PiecedFormat::Gmsh:
      return readPiecedBytes(format, FileBytes::open(path), path, options);
  }
  return {};
}

mesh::UnstructuredMesh readPiecedBytes(PiecedFormat format, const FileBytes& bytes,
                                       const std::string& name, const ReadOptions& options) {
  checkNoClusterArray(name, options);
  switch (format) {
    case PiecedFormat::Su2:
      return withoutPointOrigins(readSu2(bytes, name, options));
    case PiecedFormat::Gmsh:
      return withoutPointOrigins(readGmsh(bytes, name, options));
    case PiecedFormat::Cgns:
    case PiecedFormat::Exodus:
      break;
  }
  throw Error(name, ": ", piecedFormatDescription(format),
              " files are read through their library from a file; read it with readMesh");
}

std::vector<float> piecedFieldStep(PiecedFormat format, const std::string& path,
                                   const std::string& field, uint64_t step,
                                   const ReadOptions& options) {
  ReadOptions o = options;
  o.fields = {field};
  o.loadFields = true;
  o.step.reset();
  const std::vector<FieldStepCount> listed = piecedFieldSteps(path, piecedLayout(format, path), o);
  if (listed.size() != 1 || listed[0].cellData || step >= listed[0].steps)
    throw FileError(path, "point field '", field, "' has ",
                    listed.empty() || listed[0].cellData ? 0 : listed[0].steps,
                    " time steps, not step ", step);
  o.step = step;  // only that step is read, not every step up to it
  mesh::UnstructuredMesh m = readPieced(format, path, o);
  if (m.fields.size() != 1 || m.fields[0].steps.empty())
    throw FileError(path, "point field '", field, "' step ", step, " was not read");
  return std::move(m.fields[0].steps[0]);
}

std::vector<FieldStepCount> piecedFieldSteps(const std::string& path, const PiecedLayout& layout,
                                             const ReadOptions& options) {
  std::vector<FieldStepCount> out;
  if (!options.loadFields) return out;
  if (options.fields.empty()) {
    for (const FieldStepCount& f : layout.fields)
      if (!f.cellData) out.push_back(f);
    return out;
  }
  for (const std::string& request : options.fields) {
    if (const FieldStepCount* f = findField(layout, request, false)) {
      out.push_back(*f);
      continue;
    }
    if (auto split = splitComponent(request)) {
      const FieldStepCount* f = findField(layout, split->first, false);
      if (!f) f = findField(layout, split->first, true);
      if (f && f->components > 1 && split->second >= 0 && uint32_t(split->second) < f->components) {
        out.push_back({request, f->steps, f->cellData, 0});
        continue;
      }
      if (f)
        throw FileError(path, "field '", split->first, "' has ", std::max(f->components, 1u),
                        " components, not component ", split->second);
    }
    if (const FieldStepCount* f = findField(layout, request, true)) {
      out.push_back(*f);
      continue;
    }
    throw FileError(path, "has no field '", request, "' (it has ", fieldNames(layout), ")");
  }
  return out;
}

}  // namespace sm::io
