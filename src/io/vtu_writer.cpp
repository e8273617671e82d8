// .vtu and .pvtu writer: appended raw data with a UInt64 header, optionally zlib-compressed in
// blocks (compressed in parallel), Float64 points, Int64 connectivity and offsets, UInt8 types,
// Int32 cluster ids, Float32 fields (NAME@t<K> per step when a field has several), Float64
// TimeValues field data. Array bytes are produced block by block from the mesh, never as one
// converted copy of the whole mesh.
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>

#include "common/check.h"
#include "common/error.h"
#include "common/file_util.h"
#include "io/array_plan.h"
#include "io/mesh_io.h"
#include "io/vtk_binary.h"

namespace sm::io {
namespace {

namespace fs = std::filesystem;
using mesh::CellType;

constexpr uint64_t kBlockSize = 1 << 20;  // a multiple of every element size
constexpr int kZlibLevel = 1;             // simulation data gains little from slower levels

using Fill = std::function<void(uint64_t firstByte, uint64_t bytes, uint8_t* dst)>;

struct OutArray {
  std::string parent;  // FieldData, PointData, CellData, Points or Cells
  std::string attributes;
  uint64_t bytes = 0;
  Fill fill;
  std::vector<uint8_t> compressed;  // header and blocks, when compressing
  uint64_t encodedSize = 0;
};

std::string xmlEscape(const std::string& s) {
  std::string r;
  for (char c : s) {
    switch (c) {
      case '&':
        r += "&amp;";
        break;
      case '<':
        r += "&lt;";
        break;
      case '>':
        r += "&gt;";
        break;
      case '"':
        r += "&quot;";
        break;
      default:
        r += c;
    }
  }
  return r;
}

// The array holding step s of f: NAME@t<s> when f has several steps, or when its name alone
// would read back as a step (a one-step field "p@t3" is written "p@t3@t0").
std::string arrayName(const mesh::Field& f, uint64_t s) {
  return f.numSteps() > 1 || splitStepName(f.name).step ? concat(f.name, "@t", s) : f.name;
}

std::string arrayName(const mesh::CellField& f, uint64_t s) {
  return f.steps.size() > 1 || splitStepName(f.name).step ? concat(f.name, "@t", s) : f.name;
}

// An array of `count` values of T; fill(first, n, out) writes values [first, first + n).
template <class T>
OutArray makeArray(std::string parent, std::string attributes, uint64_t count,
                   std::function<void(uint64_t, uint64_t, T*)> fill) {
  OutArray a{std::move(parent), std::move(attributes), count * sizeof(T), {}, {}, 0};
  a.fill = [fill = std::move(fill)](uint64_t b, uint64_t n, uint8_t* dst) {
    fill(b / sizeof(T), n / sizeof(T), reinterpret_cast<T*>(dst));
  };
  return a;
}

// Cells of all types as one list in type order (tetrahedra, pyramids, wedges, hexahedra).
struct CellRanges {
  uint64_t firstCell[mesh::kNumCellTypes + 1] = {};
  uint64_t firstId[mesh::kNumCellTypes + 1] = {};
  explicit CellRanges(const mesh::UnstructuredMesh& m) {
    for (int t = 0; t < mesh::kNumCellTypes; ++t) {
      firstCell[t + 1] = firstCell[t] + m.numCells(mesh::kAllCellTypes[t]);
      firstId[t + 1] = firstId[t] + m.cells[t].size();
    }
  }
  int typeOfCell(uint64_t c) const {
    int t = 0;
    while (c >= firstCell[t + 1]) ++t;
    return t;
  }
  int typeOfId(uint64_t i) const {
    int t = 0;
    while (i >= firstId[t + 1]) ++t;
    return t;
  }
};

std::string dataArray(const char* type, const std::string& name, uint32_t components = 1) {
  std::string s = concat("type=\"", type, "\" Name=\"", xmlEscape(name), "\"");
  if (components > 1) s += concat(" NumberOfComponents=\"", components, "\"");
  return s;
}

void addCellArrays(std::vector<OutArray>& out, const mesh::UnstructuredMesh& m) {
  auto r = std::make_shared<CellRanges>(m);
  const uint64_t nCells = r->firstCell[mesh::kNumCellTypes], nIds = r->firstId[mesh::kNumCellTypes];
  out.push_back(makeArray<int64_t>("Cells", dataArray("Int64", "connectivity"), nIds,
                                   [&m, r](uint64_t b, uint64_t n, int64_t* o) {
                                     for (uint64_t i = b; i < b + n; ++i) {
                                       int t = r->typeOfId(i);
                                       o[i - b] = m.cells[t][i - r->firstId[t]];
                                     }
                                   }));
  out.push_back(makeArray<int64_t>(
      "Cells", dataArray("Int64", "offsets"), nCells, [r](uint64_t b, uint64_t n, int64_t* o) {
        for (uint64_t c = b; c < b + n; ++c) {
          int t = r->typeOfCell(c);
          uint64_t nv = mesh::numVerts(mesh::kAllCellTypes[t]);
          o[c - b] = int64_t(r->firstId[t] + (c - r->firstCell[t] + 1) * nv);
        }
      }));
  out.push_back(makeArray<uint8_t>(
      "Cells", dataArray("UInt8", "types"), nCells, [r](uint64_t b, uint64_t n, uint8_t* o) {
        for (uint64_t c = b; c < b + n; ++c)
          o[c - b] = uint8_t(mesh::toVtkType(mesh::kAllCellTypes[r->typeOfCell(c)]));
      }));
  out.push_back(makeArray<int32_t>("CellData", dataArray("Int32", "cluster"), nCells,
                                   [&m, r](uint64_t b, uint64_t n, int32_t* o) {
                                     for (uint64_t c = b; c < b + n; ++c) {
                                       int t = r->typeOfCell(c);
                                       o[c - b] = m.clusters[t][c - r->firstCell[t]];
                                     }
                                   }));
  // Cell data, written in the cells' order (type after type), one array per step.
  for (const mesh::CellField& f : m.cellFields)
    for (uint64_t s = 0; s < f.steps.size(); ++s) {
      const auto* perType = &f.steps[s];
      for (int t = 0; t < mesh::kNumCellTypes; ++t)
        SM_CHECK_EQ((*perType)[t].size(), m.numCells(mesh::kAllCellTypes[t]));
      out.push_back(makeArray<float>("CellData", dataArray("Float32", arrayName(f, s)), nCells,
                                     [perType, r](uint64_t b, uint64_t n, float* o) {
                                       for (uint64_t c = b; c < b + n; ++c) {
                                         int t = r->typeOfCell(c);
                                         o[c - b] = (*perType)[t][c - r->firstCell[t]];
                                       }
                                     }));
    }
}

std::vector<OutArray> meshArrays(const mesh::UnstructuredMesh& m) {
  std::vector<OutArray> out;
  if (!m.timeValues.empty()) {
    OutArray t = makeArray<double>("FieldData", dataArray("Float64", "TimeValues"),
                                   m.timeValues.size(), [&m](uint64_t b, uint64_t n, double* o) {
                                     std::memcpy(o, m.timeValues.data() + b, n * sizeof(double));
                                   });
    t.attributes += concat(" NumberOfTuples=\"", m.timeValues.size(), "\"");
    out.push_back(std::move(t));
  }
  for (const mesh::Field& f : m.fields) {
    for (uint64_t s = 0; s < f.numSteps(); ++s) {
      SM_CHECK_EQ(f.steps[s].size(), m.points.size());
      const std::string name = arrayName(f, s);
      const std::vector<float>* v = &f.steps[s];
      out.push_back(makeArray<float>("PointData", dataArray("Float32", name), v->size(),
                                     [v](uint64_t b, uint64_t n, float* o) {
                                       std::memcpy(o, v->data() + b, n * sizeof(float));
                                     }));
    }
  }
  out.push_back(makeArray<double>("Points", dataArray("Float64", "Points", 3), 3 * m.points.size(),
                                  [&m](uint64_t b, uint64_t n, double* o) {
                                    std::memcpy(o, &m.points[0].x + b, n * sizeof(double));
                                  }));
  addCellArrays(out, m);
  return out;
}

std::string xmlHeader(const mesh::UnstructuredMesh& m, const std::vector<OutArray>& arrays,
                      bool compress) {
  std::string x = concat(
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"",
      std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian",
      "\" header_type=\"UInt64\"", compress ? " compressor=\"vtkZLibDataCompressor\"" : "",
      ">\n  <UnstructuredGrid>\n");
  uint64_t offset = 0;
  auto section = [&](const std::string& parent, const std::string& indent) {
    std::string s;
    for (const OutArray& a : arrays) {
      if (a.parent == parent)
        s += concat(indent, "<DataArray ", a.attributes, " format=\"appended\" offset=\"", offset,
                    "\"/>\n");
      if (a.parent == parent) offset += a.encodedSize;
    }
    return s;
  };
  std::string fd = section("FieldData", "      ");
  if (!fd.empty()) x += "    <FieldData>\n" + fd + "    </FieldData>\n";
  x += concat("    <Piece NumberOfPoints=\"", m.points.size(), "\" NumberOfCells=\"", m.numCells(),
              "\">\n");
  x += "      <PointData>\n" + section("PointData", "        ") + "      </PointData>\n";
  x += "      <CellData>\n" + section("CellData", "        ") + "      </CellData>\n";
  x += "      <Points>\n" + section("Points", "        ") + "      </Points>\n";
  x += "      <Cells>\n" + section("Cells", "        ") + "      </Cells>\n";
  x += "    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _";
  return x;
}

// Arrays in the order their offsets were assigned by xmlHeader.
std::vector<const OutArray*> inOffsetOrder(const std::vector<OutArray>& arrays) {
  std::vector<const OutArray*> order;
  for (const char* parent : {"FieldData", "PointData", "CellData", "Points", "Cells"})
    for (const OutArray& a : arrays)
      if (a.parent == parent) order.push_back(&a);
  return order;
}

void writeArrays(std::FILE* f, const std::vector<OutArray>& arrays, bool compress) {
  std::vector<uint8_t> chunk;
  for (const OutArray* a : inOffsetOrder(arrays)) {
    if (compress) {
      std::fwrite(a->compressed.data(), 1, a->compressed.size(), f);
      continue;
    }
    uint64_t header = a->bytes;
    if constexpr (std::endian::native == std::endian::big) header = byteSwap(header);
    std::fwrite(&header, 8, 1, f);
    chunk.resize(std::min(a->bytes, kBlockSize));
    for (uint64_t b = 0; b < a->bytes; b += kBlockSize) {
      uint64_t n = std::min(kBlockSize, a->bytes - b);
      a->fill(b, n, chunk.data());
      std::fwrite(chunk.data(), 1, n, f);
    }
  }
}

void writeOne(const std::string& path, const mesh::UnstructuredMesh& m,
              const WriteOptions& options) {
  std::vector<OutArray> arrays = meshArrays(m);
  for (OutArray& a : arrays) {
    if (options.compress) {
      a.compressed = compressBlocks(a.bytes, kBlockSize, kZlibLevel, options.threads, a.fill);
      a.encodedSize = a.compressed.size();
    } else {
      a.encodedSize = 8 + a.bytes;
    }
  }
  const std::string header = xmlHeader(m, arrays, options.compress);
  writeFileAtomically(path, [&](const std::string& tmp) {
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw FileError(path, "cannot create: ", std::strerror(errno));
    std::fwrite(header.data(), 1, header.size(), f);
    writeArrays(f, arrays, options.compress);
    static const char kTail[] = "\n  </AppendedData>\n</VTKFile>\n";
    std::fwrite(kTail, 1, sizeof kTail - 1, f);
    bool ok = !std::ferror(f);
    ok = std::fclose(f) == 0 && ok;
    if (!ok) throw FileError(path, "write failed (disk full?)");
  });
}

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

}  // namespace

void writeVtu(const std::string& path, const mesh::UnstructuredMesh& mesh,
              const WriteOptions& options) {
  writeOne(path, mesh, options);
}

namespace {

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

void writePvtu(const std::string& path, const mesh::UnstructuredMesh& mesh,
               const WriteOptions& options) {
  const fs::path p(path);
  const std::string stem = p.stem().string();
  const fs::path folder = p.parent_path() / stem;
  std::error_code ec;
  // Checked before any piece is written: the index is written last, and failing then would leave
  // pieces without one.
  if (fs::exists(p, ec) && !fs::is_regular_file(p, ec))
    throw FileError(path, "cannot write: exists and is not a regular file");
  // One piece per cluster id, empty ones included: sparse ids would mean absurdly many files.
  if (uint64_t(mesh.numClusters()) > mesh.numCells() + 4096)
    throw Error(path, ": the mesh numbers its clusters up to ", mesh.numClusters() - 1,
                " but has only ", mesh.numCells(), " cells; renumber them before writing pieces");
  const bool created = fs::create_directories(folder, ec);
  if (ec)
    throw FileError(folder.string(), "cannot create the folder for the pieces: ", ec.message());
  StagedPieces staged(folder, created);
  const auto byCluster = cellsByCluster(mesh);
  std::vector<uint32_t> local(mesh.points.size(), 0xFFFFFFFFu);
  std::string pieces;
  for (size_t k = 0; k < byCluster.size(); ++k) {
    const std::string file = concat(stem, "_", k, ".vtu");
    writeOne(staged.stage(folder / file), extractPiece(mesh, int32_t(k), byCluster[k], local),
             options);
    pieces += concat("    <Piece Source=\"", xmlEscape(stem + "/" + file), "\"/>\n");
  }
  const std::string x = pvtuIndex(mesh, pieces);
  writeBytesAtomically(staged.stage(p), {reinterpret_cast<const uint8_t*>(x.data()), x.size()});
  staged.commit();
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
  }
  const std::string x =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n" +
      sets + "  </Collection>\n</VTKFile>\n";
  writeBytesAtomically(path, {reinterpret_cast<const uint8_t*>(x.data()), x.size()});
}

}  // namespace sm::io
