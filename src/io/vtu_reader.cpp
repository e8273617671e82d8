// .vtu reader: assembles the mesh from a VtuDocument. A file may hold several <Piece>s; they are
// read as one mesh (points of later pieces numbered after earlier ones, file cell numbers running
// on), as VTK's own reader does.
#include <algorithm>
#include <cstring>

#include "common/error.h"
#include "common/log.h"
#include "io/ghost_cells.h"
#include "io/polyhedra.h"
#include "io/readers.h"
#include "io/vtu_arrays.h"
#include "io/vtu_document.h"
#include "io_core/array_plan.h"
#include "io_core/text_scan.h"
#include "mesh/mesh_builder.h"

namespace sm::io {
namespace {

using Piece = VtuPiece;

// Ids handed to the builder per cell; volume cells need at most 27 (triquadratic hexahedron).
constexpr int64_t kMaxIds = 32;
constexpr int kPolyhedron = 42;

std::string quoted(std::string_view what, std::string_view name) {
  return concat(what, " '", name, "'");
}

class VtuReader {
 public:
  VtuReader(const VtuDocument& doc, const ReadOptions& options, std::optional<int32_t> pieceCluster)
      : doc_(doc),
        src_(doc.source()),
        options_(options),
        pieceCluster_(pieceCluster),
        builder_(src_) {}

  mesh::UnstructuredMesh read() {
    findPieces();
    uint64_t fileCells = 0;
    for (const Piece& p : pieces_) fileCells += p.numCells;
    if (options_.cellOrigins)
      builder_.keepCellOrigins(fileCells);
    else
      builder_.setFileCells(fileCells);  // kept for polyhedra only
    cellArrays_ = dataCellArrays(vtuCellArrayNames(pieces_[0]), options_);
    builder_.setCellArrays(cellArrays_);
    readPoints();
    readCells();
    if (!pieceCluster_) readClusters();
    readFields();
    readTimeValues();
    return builder_.finish();
  }

 private:
  void findPieces() { pieces_ = vtuPieces(doc_); }

  void readPoints() {
    std::vector<glm::dvec3> all;
    for (size_t k = 0; k < pieces_.size(); ++k) {
      const Piece& p = pieces_[k];
      if (p.numPoints == 0) continue;
      pugi::xml_node arr = p.node.child("Points").child("DataArray");
      if (!arr) throw FileError(src_, "piece ", k, " has ", p.numPoints, " points but no <Points>");
      std::vector<glm::dvec3> pts =
          toPoints(doc_.decode(arr, p.numPoints, "points", 3), options_.threads);
      if (all.empty())
        all = std::move(pts);
      else
        all.insert(all.end(), pts.begin(), pts.end());
    }
    builder_.setPoints(std::move(all));
  }

  void readCells() {
    for (size_t k = 0; k < pieces_.size(); ++k) {
      const Piece& p = pieces_[k];
      if (p.numCells == 0) continue;
      pugi::xml_node cells = p.node.child("Cells");
      auto need = [&](const char* name) {
        pugi::xml_node a = findDataArray(cells, name);
        if (!a) throw FileError(src_, "has ", p.numCells, " cells but no '", name, "' array");
        return a;
      };
      std::vector<int64_t> offsets = toInt64(
          doc_.decode(need("offsets"), p.numCells, "cell offsets", 1), src_, "cell offsets");
      std::vector<int64_t> types =
          toInt64(doc_.decode(need("types"), p.numCells, "cell types", 1), src_, "cell types");
      int64_t prev = 0;
      for (uint64_t c = 0; c < p.numCells; ++c) {
        if (offsets[c] < prev)
          throw FileError(src_, "cell offsets: offset of cell ", p.firstCell + c, " (", offsets[c],
                          ") is ", offsets[c] < 0 ? "negative" : "smaller than the one before");
        prev = offsets[c];
      }
      NumericArray conn = doc_.decode(need("connectivity"), uint64_t(prev), "cell connectivity", 1);
      // Named as the file declares it: ascii arrays are decoded to a wider type.
      if (isFloatType(conn.type))
        throw FileError(src_, "cell connectivity has type ",
                        printable(need("connectivity").attribute("type").value()),
                        "; point ids must be integers");
      std::vector<int64_t> ghost;
      if (pugi::xml_node g = findDataArray(p.node.child("CellData"), "vtkGhostType"))
        ghost = toInt64(doc_.decode(g, p.numCells, "cell array 'vtkGhostType'", 1), src_,
                        "vtkGhostType");
      reserve(types);
      const VtuPolyhedra polyhedra(doc_, cells, types);
      visitArray(conn, [&](auto tag, auto swap) {
        using T = typename decltype(tag)::type;
        if constexpr (std::is_integral_v<T>)
          addCells<T, decltype(swap)::value>(p, conn.data, offsets, types, ghost, polyhedra);
      });
    }
    ghostCells_.warn(src_);
  }

  void reserve(const std::vector<int64_t>& types) {
    uint64_t n[mesh::kNumCellTypes] = {};
    for (int64_t t : types)
      if (auto ct = mesh::fromVtkType(static_cast<int>(std::clamp<int64_t>(t, -1, 255))))
        ++n[mesh::typeIndex(*ct)];
    for (mesh::CellType t : mesh::kAllCellTypes) builder_.reserveCells(t, n[mesh::typeIndex(t)]);
  }

  template <class T, bool Swap>
  void addCells(const Piece& p, const uint8_t* conn, const std::vector<int64_t>& offsets,
                const std::vector<int64_t>& types, const std::vector<int64_t>& ghost,
                const VtuPolyhedra& polyhedra) {
    int64_t ids[kMaxIds];
    int64_t begin = 0;
    const int32_t cluster = pieceCluster_.value_or(0);
    for (uint64_t c = 0; c < p.numCells; ++c) {
      const int64_t end = offsets[c];
      const uint64_t fileCell = p.firstCell + c;
      if (ghostCells_.skip(ghost, c)) {
        begin = end;
        continue;
      }
      const int64_t n = std::min(end - begin, kMaxIds);
      for (int64_t i = 0; i < n; ++i) {
        T v = loadAs<T, Swap>(conn + (begin + i) * sizeof(T));
        // Checked against this piece's points, so that no id can reach into another piece.
        bool negative = false;
        if constexpr (std::is_signed_v<T>) negative = v < 0;
        if (negative || uint64_t(v) >= p.numPoints)
          throw FileError(src_, "cell ", fileCell, " refers to point ", +v, " but ",
                          pieces_.size() > 1 ? "its piece has " : "the file has ", p.numPoints,
                          " points");
        ids[i] = static_cast<int64_t>(v) + static_cast<int64_t>(p.firstPoint);
      }
      const int vtkType = static_cast<int>(std::clamp<int64_t>(types[c], -1, 1 << 20));
      if (vtkType == kPolyhedron && polyhedra.hasFaces()) {
        if (auto faces = polyhedra.faces(c, fileCell, p.numPoints, p.firstPoint))
          builder_.addPolyhedron(*faces, fileCell, cluster);
        else
          builder_.skipPolyhedron(fileCell, mesh::PolyhedronSplit::TooLarge);
      } else
        builder_.addVtkCell(vtkType, {ids, static_cast<size_t>(n)}, fileCell, cluster);
      begin = end;
    }
  }

  void readClusters() {
    std::vector<std::string> names = vtuCellArrayNames(pieces_[0]);
    auto chosen = chooseClusterArray(src_, names, options_);
    if (!chosen) return;
    const std::string& name = names[*chosen];
    std::vector<int64_t> ids;
    for (const Piece& p : pieces_) {
      pugi::xml_node a = findDataArray(p.node.child("CellData"), name);
      if (!a) throw FileError(src_, "a piece lacks the cell array '", name, "'");
      std::vector<int64_t> v = toInt64(doc_.decode(a, p.numCells, quoted("cell array", name), 1),
                                       src_, quoted("cell array", name));
      ids.insert(ids.end(), v.begin(), v.end());
    }
    builder_.setClusterIds(ids, name);
  }

  void readFields() {
    if (!options_.loadFields) return;
    std::vector<ArrayInfo> infos = vtuPointArrays(doc_, pieces_[0]);
    // Cell arrays are looked at only when fields are named: only then can one be a field.
    const std::vector<ArrayInfo> cellInfos =
        options_.fields.empty() ? std::vector<ArrayInfo>{} : vtuCellArrays(doc_, pieces_[0]);
    const FieldSplit split = splitFieldRequests(infos, cellInfos, options_);
    readCellFields(cellInfos, split.cells);
    for (const FieldLoad& load : planFields(src_, infos, split.points, &cellArrays_))
      builder_.addFieldStep(load.field, load.step, piecesValues(Data::Points, infos, load));
  }

  // Cell data asked for as fields: one value per file cell, kept for the cells kept.
  void readCellFields(const std::vector<ArrayInfo>& infos, const ReadOptions& cells) {
    for (const FieldLoad& load : planFields(src_, infos, cells, nullptr, "cell"))
      builder_.addCellFieldStep(load.field, load.step, piecesValues(Data::Cells, infos, load));
  }

  enum class Data { Points, Cells };

  // One load's values from every piece, one after another (points or cells of the whole file).
  std::vector<float> piecesValues(Data data, const std::vector<ArrayInfo>& infos,
                                  const FieldLoad& load) {
    const bool cells = data == Data::Cells;
    const std::string& name = infos[load.array].name;
    const char* what = cells ? "cell array" : "point array";
    std::vector<float> values;
    const ArrayName array{src_, cells ? "cell" : "point", name};
    for (const Piece& p : pieces_) {
      pugi::xml_node a = findDataArray(p.node.child(cells ? "CellData" : "PointData"), name);
      if (!a) throw FileError(src_, "a piece lacks the ", what, " '", name, "'");
      std::vector<float> v = toFloats(doc_.decode(a, cells ? p.numCells : p.numPoints,
                                                  quoted(what, name), infos[load.array].components),
                                      load.component, options_.threads, &array);
      if (values.empty())
        values = std::move(v);
      else
        values.insert(values.end(), v.begin(), v.end());
    }
    return values;
  }

  void readTimeValues() {
    pugi::xml_node fd = doc_.root().child("UnstructuredGrid").child("FieldData");
    for (pugi::xml_node a : fd.children("DataArray")) {
      std::string_view name = a.attribute("Name").value();
      if (!isTimeValuesArray(name)) continue;
      uint64_t n = a.attribute("NumberOfTuples") ? doc_.count(a, "NumberOfTuples") : 1;
      NumericArray t = doc_.decode(a, n, quoted("field data", name), 1);
      std::vector<double> times(n);
      visitArray(t, [&](auto tag, auto swap) {
        using T = typename decltype(tag)::type;
        for (uint64_t i = 0; i < n; ++i)
          times[i] = static_cast<double>(loadAs<T, decltype(swap)::value>(t.data + i * sizeof(T)));
      });
      builder_.setTimeValues(std::move(times));
      return;
    }
  }

  const VtuDocument& doc_;
  const std::string& src_;
  const ReadOptions& options_;
  std::optional<int32_t> pieceCluster_;
  mesh::MeshBuilder builder_;
  std::vector<Piece> pieces_;
  GhostCells ghostCells_;
  std::vector<std::string> cellArrays_;  // data cell arrays (not read; messages)
};

}  // namespace

mesh::UnstructuredMesh readVtu(FileBytes bytes, const std::string& source,
                               const ReadOptions& options, std::optional<int32_t> pieceCluster) {
  if (pieceCluster) checkPieceIsNotAnIndex(bytes.span(), source);
  VtuDocument doc(bytes, source, "UnstructuredGrid", options.threads, options.stopRequested);
  return VtuReader(doc, options, pieceCluster).read();
}

}  // namespace sm::io
