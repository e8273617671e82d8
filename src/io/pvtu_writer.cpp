// .pvtu and .pvd writers: a piece per cluster (each written by writeVtu's code), staged and
// renamed into place only once all are complete; a series as a .pvtu per step.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "common/check.h"
#include "common/error.h"
#include "common/file_util.h"
#include "common/progress.h"
#include "io/mesh_io.h"
#include "io/vtk_xml_names.h"

namespace sm::io {
namespace {

namespace fs = std::filesystem;

// The cells of each cluster, by type.
std::vector<std::array<std::vector<uint32_t>, mesh::kNumCellTypes>> cellsByCluster(
    const mesh::UnstructuredMesh& m) {
  std::vector<std::array<std::vector<uint32_t>, mesh::kNumCellTypes>> by(
      std::max(m.numClusters(), 1));
  for (int t = 0; t < mesh::kNumCellTypes; ++t)
    for (size_t c = 0; c < m.clusters[t].size(); ++c)
      by[m.clusters[t][c]][t].push_back(uint32_t(c));
  return by;
}

// Cluster k alone: the points its cells use, in the order of the whole mesh, renumbered.
mesh::UnstructuredMesh extractPiece(
    const mesh::UnstructuredMesh& m, int32_t k,
    const std::array<std::vector<uint32_t>, mesh::kNumCellTypes>& cells,
    std::vector<uint32_t>& local) {
  mesh::UnstructuredMesh p;
  p.source = m.source;
  p.timeValues = m.timeValues;
  std::vector<uint32_t> used;
  for (int t = 0; t < mesh::kNumCellTypes; ++t) {
    const uint32_t nv = mesh::numVerts(mesh::kAllCellTypes[t]);
    for (uint32_t c : cells[t])
      for (uint32_t v = 0; v < nv; ++v) {
        uint32_t id = m.cells[t][size_t(c) * nv + v];
        if (local[id] == 0xFFFFFFFFu) {
          local[id] = 0;
          used.push_back(id);
        }
      }
  }
  std::sort(used.begin(), used.end());
  for (uint32_t i = 0; i < used.size(); ++i) local[used[i]] = i;
  for (uint32_t id : used) p.points.push_back(m.points[id]);
  for (int t = 0; t < mesh::kNumCellTypes; ++t) {
    const uint32_t nv = mesh::numVerts(mesh::kAllCellTypes[t]);
    for (uint32_t c : cells[t])
      for (uint32_t v = 0; v < nv; ++v) p.cells[t].push_back(local[m.cells[t][size_t(c) * nv + v]]);
    p.clusters[t].assign(cells[t].size(), k);
  }
  for (const mesh::Field& f : m.fields) {
    mesh::Field pf{f.name, std::vector<std::vector<float>>(f.numSteps())};
    for (uint64_t s = 0; s < f.numSteps(); ++s)
      for (uint32_t id : used) pf.steps[s].push_back(f.steps[s][id]);
    p.fields.push_back(std::move(pf));
  }
  for (const mesh::CellField& f : m.cellFields) {
    mesh::CellField pf{f.name, decltype(f.steps)(f.steps.size())};
    for (size_t s = 0; s < f.steps.size(); ++s)
      for (int t = 0; t < mesh::kNumCellTypes; ++t)
        for (uint32_t c : cells[t]) pf.steps[s][t].push_back(f.steps[s][t][c]);
    p.cellFields.push_back(std::move(pf));
  }
  for (uint32_t id : used) local[id] = 0xFFFFFFFFu;  // ready for the next piece
  return p;
}

// Pieces and index are written under staging names and renamed into place only once every one is
// complete, the index last: a failure part way (disk full, a folder where a piece goes) then
// leaves an existing data set of the same name as it was, instead of some of its pieces replaced
// by the new mesh's. (Pieces of an older, larger set beyond the new count stay, unnamed.)
class StagedPieces {
 public:
  StagedPieces(fs::path folder, bool createdFolder)
      : folder_(std::move(folder)), createdFolder_(createdFolder) {}
  StagedPieces(const StagedPieces&) = delete;
  StagedPieces& operator=(const StagedPieces&) = delete;
  ~StagedPieces() {
    if (committed_) return;
    std::error_code ec;
    for (const auto& [staged, target] : files_) fs::remove(staged, ec);
    if (createdFolder_) fs::remove(folder_, ec);  // only if empty
  }
  // Where to write the file that belongs at `target` now.
  std::string stage(const fs::path& target) {
    std::error_code ec;
    if (fs::exists(target, ec) && !fs::is_regular_file(target, ec))
      throw FileError(target.string(), "cannot write: exists and is not a regular file");
    files_.emplace_back(fs::path(target.string() + ".staged"), target);
    return files_.back().first.string();
  }
  void commit() {
    for (const auto& [staged, target] : files_) {
      std::error_code ec;
      fs::rename(staged, target, ec);
      if (ec) throw FileError(target.string(), "cannot write: ", ec.message());
    }
    committed_ = true;
  }

 private:
  fs::path folder_;
  bool createdFolder_;
  std::vector<std::pair<fs::path, fs::path>> files_;  // (staged, target)
  bool committed_ = false;
};

std::string pvtuIndex(const mesh::UnstructuredMesh& mesh, const std::string& pieces) {
  std::string x =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"";
  x += std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";
  x += "\" header_type=\"UInt64\">\n  <PUnstructuredGrid GhostLevel=\"0\">\n    <PPointData>\n";
  for (const mesh::Field& f : mesh.fields)
    for (uint64_t s = 0; s < f.numSteps(); ++s)
      x += concat("      <PDataArray ", dataArray("Float32", arrayName(f, s)), "/>\n");
  x += "    </PPointData>\n    <PCellData>\n      <PDataArray " + dataArray("Int32", "cluster") +
       "/>\n";
  for (const mesh::CellField& f : mesh.cellFields)
    for (uint64_t s = 0; s < f.steps.size(); ++s)
      x += concat("      <PDataArray ", dataArray("Float32", arrayName(f, s)), "/>\n");
  x += "    </PCellData>\n    <PPoints>\n      <PDataArray " + dataArray("Float64", "Points", 3) +
       "/>\n    </PPoints>\n" + pieces + "  </PUnstructuredGrid>\n</VTKFile>\n";
  return x;
}

}  // namespace

struct PvtuPieceWriter::Impl {
  fs::path path, folder;
  std::string stem;
  mesh::UnstructuredMesh layout;  // names, step counts and times; no geometry
  WriteOptions options;
  std::vector<std::string> staged;  // per piece
  std::unique_ptr<StagedPieces> pieces;
  bool finished = false;
};

PvtuPieceWriter::PvtuPieceWriter(const std::string& path, uint64_t pieces,
                                 const mesh::UnstructuredMesh& layout, const WriteOptions& options)
    : impl_(std::make_unique<Impl>()) {
  Impl& w = *impl_;
  w.path = fs::path(path);
  w.stem = w.path.stem().string();
  w.folder = w.path.parent_path() / w.stem;
  w.options = options;
  w.layout.source = layout.source;
  w.layout.timeValues = layout.timeValues;
  for (const mesh::Field& f : layout.fields)
    w.layout.fields.push_back({f.name, std::vector<std::vector<float>>(f.numSteps())});
  for (const mesh::CellField& f : layout.cellFields)
    w.layout.cellFields.push_back({f.name, decltype(f.steps)(f.steps.size())});
  std::error_code ec;
  // Checked before any piece is written: the index is written last, and failing then would leave
  // pieces without one.
  if (fs::exists(w.path, ec) && !fs::is_regular_file(w.path, ec))
    throw FileError(path, "cannot write: exists and is not a regular file");
  const bool created = fs::create_directories(w.folder, ec);
  if (ec)
    throw FileError(w.folder.string(), "cannot create the folder for the pieces: ", ec.message());
  w.pieces = std::make_unique<StagedPieces>(w.folder, created);
  // Staged names are handed out here, so that write() may run on several threads at once.
  for (uint64_t k = 0; k < pieces; ++k)
    w.staged.push_back(w.pieces->stage(w.folder / pieceFileName(k)));
}

PvtuPieceWriter::~PvtuPieceWriter() = default;

std::string PvtuPieceWriter::pieceFileName(uint64_t k) const {
  return concat(impl_->stem, "_", k, ".vtu");
}

void PvtuPieceWriter::write(uint64_t k, const mesh::UnstructuredMesh& piece) {
  SM_CHECK_LT(k, impl_->staged.size());
  writeVtu(impl_->staged[k], piece, impl_->options);
}

void PvtuPieceWriter::finish() {
  Impl& w = *impl_;
  SM_CHECK(!w.finished);
  std::string pieces;
  for (uint64_t k = 0; k < w.staged.size(); ++k)
    pieces += concat("    <Piece Source=\"", xmlEscape(w.stem + "/" + pieceFileName(k)), "\"/>\n");
  const std::string x = pvtuIndex(w.layout, pieces);
  writeBytesAtomically(w.pieces->stage(w.path),
                       {reinterpret_cast<const uint8_t*>(x.data()), x.size()});
  w.pieces->commit();
  w.finished = true;
}

void writePvtu(const std::string& path, const mesh::UnstructuredMesh& mesh,
               const WriteOptions& options) {
  // One piece per cluster id, empty ones included: sparse ids would mean absurdly many files.
  if (uint64_t(mesh.numClusters()) > mesh.numCells() + 4096)
    throw Error(path, ": the mesh numbers its clusters up to ", mesh.numClusters() - 1,
                " but has only ", mesh.numCells(), " cells; renumber them before writing pieces");
  for (mesh::CellType t : mesh::kAllCellTypes)  // cellsByCluster numbers them in 32 bits
    if (mesh.numCells(t) > 0xFFFFFFFFull)
      throw Error(path, ": ", mesh.numCells(t), " ", mesh::cellTypePluralName(t),
                  " in one mesh; writing pieces from one mesh holds at most 4294967295 of a type");
  const auto byCluster = cellsByCluster(mesh);
  PvtuPieceWriter writer(path, byCluster.size(), mesh, options);
  std::vector<uint32_t> local(mesh.points.size(), 0xFFFFFFFFu);
  Progress progress("piece written", byCluster.size());
  for (size_t k = 0; k < byCluster.size(); ++k) {
    writer.write(k, extractPiece(mesh, int32_t(k), byCluster[k], local));
    progress.advance();
  }
  writer.finish();
}

// A time series the way solvers write one: a .pvtu per step, holding its fields at that step, and
// a ParaView data collection naming them with their times (ParaView and VisIt open it as such).
void writePvdSeries(const std::string& path, const mesh::UnstructuredMesh& mesh,
                    const WriteOptions& options) {
  const fs::path p(path);
  const std::string stem = p.stem().string();
  uint64_t steps = std::max<uint64_t>(1, mesh.numSteps());
  for (const mesh::CellField& f : mesh.cellFields)
    steps = std::max<uint64_t>(steps, f.steps.size());
  if (!mesh.timeValues.empty() && mesh.timeValues.size() != steps)
    throw Error(path, ": the mesh has ", steps, " time steps but ", mesh.timeValues.size(),
                " time values");
  // Readers order a series by time: times out of order would come back as other steps.
  for (size_t k = 0; k < mesh.timeValues.size(); ++k)
    if (!std::isfinite(mesh.timeValues[k]) ||
        (k > 0 && !(mesh.timeValues[k] > mesh.timeValues[k - 1])))
      throw Error(path, ": time value ", k, " (", mesh.timeValues[k],
                  ") is not finite and after the one before; a series needs increasing times");
  std::error_code ec;
  if (fs::exists(p, ec) && !fs::is_regular_file(p, ec))
    throw FileError(path, "cannot write: exists and is not a regular file");
  // One copy of the geometry, whose fields hold one step at a time.
  mesh::UnstructuredMesh step;
  step.source = mesh.source;
  step.points = mesh.points;
  step.cells = mesh.cells;
  step.clusters = mesh.clusters;
  for (const mesh::Field& f : mesh.fields)
    if (f.numSteps() > 0) step.fields.push_back({f.name, {}});
  for (const mesh::CellField& f : mesh.cellFields)
    if (!f.steps.empty()) step.cellFields.push_back({f.name, {}});
  std::string sets;
  Progress progress("step written", steps);
  for (uint64_t k = 0; k < steps; ++k) {
    size_t out = 0;
    for (const mesh::Field& all : mesh.fields)
      if (all.numSteps() > 0)
        step.fields[out++].steps = {all.steps[std::min<uint64_t>(k, all.numSteps() - 1)]};
    out = 0;
    for (const mesh::CellField& all : mesh.cellFields)
      if (!all.steps.empty())
        step.cellFields[out++].steps = {all.steps[std::min<uint64_t>(k, all.steps.size() - 1)]};
    const std::string file = concat(stem, "/", stem, "_t", k, ".pvtu");
    writePvtu((p.parent_path() / file).string(), step, options);
    char time[32];  // every digit: times read back exactly
    std::snprintf(time, sizeof time, "%.17g",
                  mesh.timeValues.empty() ? double(k) : mesh.timeValues[k]);
    sets += concat("    <DataSet timestep=\"", time, "\" part=\"0\" file=\"", xmlEscape(file),
                   "\"/>\n");
    progress.advance();
  }
  const std::string x =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n" +
      sets + "  </Collection>\n</VTKFile>\n";
  writeBytesAtomically(path, {reinterpret_cast<const uint8_t*>(x.data()), x.size()});
}

}  // namespace sm::io
