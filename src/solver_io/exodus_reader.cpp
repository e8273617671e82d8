// Exodus II through libexodusii (docs/FORMATS.md). Each element block is a piece (cluster), or
// each file of a decomposed mesh (NAME.e.N.i, every block of the file in one piece); a piece's
// points are the nodes its volume blocks use, so that pieces weld where blocks or files share
// nodes. Coordinates, connectivity and variables are read an array at a time: the library is
// never called per element.
#include <exodusII.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include "common/error.h"
#include "common/log.h"
#include "io_core/weld.h"
#include "mesh/mesh_builder.h"
#include "solver_io/exodus_file.h"
#include "solver_io/pieced_readers.h"

namespace sm::io {
namespace {

constexpr uint32_t kUnused = std::numeric_limits<uint32_t>::max();
constexpr size_t kMaxNodesPerElement = 64;  // ExodusBlock's limit for volume elements

// VTK's linear type of a Lagrange shape: what an element with only its corners is.
int linearVtkType(int lagrangeVtkType) {
  switch (lagrangeVtkType) {
    case 71:
      return 10;
    case 72:
      return 12;
    case 73:
      return 13;
    default:
      return 14;
  }
}

struct PieceRead {
  PieceRead(int index, std::vector<size_t> blocks, const std::string& source)
      : index(index), blocks(std::move(blocks)), builder(source) {}
  int index;                   // the piece's number in the mesh: its cluster id
  std::vector<size_t> blocks;  // into the file's blocks
  std::vector<int64_t> nodes;  // the file's node (0-based) of each point of the piece
  uint64_t fileCells = 0;      // elements of the piece's blocks, skipped ones included
  mesh::MeshBuilder builder;
};

class ExodusReader {
 public:
  ExodusReader(const std::string& path, const ReadOptions& options)
      : path_(path), options_(options), layout_(exodusLayout(path)) {
    fields_ = piecedFieldSteps(path, layout_, options);
  }

  mesh::UnstructuredMesh read() {
    const std::vector<int> chosen = choosePieces(path_, layout_.pieces.size(), options_);
    std::vector<mesh::UnstructuredMesh> meshes;
    if (exodusPiecesAreFiles(path_, layout_.files)) {
      for (int i : chosen) {
        throwIfStopped(options_.stopRequested, layout_.files[i]);
        ExodusFile file(layout_.files[i]);
        std::vector<size_t> all(file.header().blocks.size());
        for (size_t b = 0; b < all.size(); ++b) all[b] = b;
        readPieces(file, {{i, all}}, meshes);
      }
    } else {
      ExodusFile file(layout_.files[0]);
      std::vector<std::pair<int, std::vector<size_t>>> pieces;
      for (int i : chosen) pieces.push_back({i, {size_t(i)}});
      readPieces(file, pieces, meshes);
    }
    throwIfStopped(options_.stopRequested, path_);
    mesh::UnstructuredMesh m = weldPieces(path_, std::move(meshes));
    return m;
  }

 private:
  void readPieces(const ExodusFile& file,
                  const std::vector<std::pair<int, std::vector<size_t>>>& specs,
                  std::vector<mesh::UnstructuredMesh>& out) {
    const ExodusHeader& h = file.header();
    if (h.blocks.size() != layout_.pieces.size() && !exodusPiecesAreFiles(path_, layout_.files))
      throw FileError(file.path(), "changed while it was read");
    readCoordinates(file);
    local_.assign(size_t(h.nodes), kUnused);
    std::vector<PieceRead> pieces;
    pieces.reserve(specs.size());
    for (const auto& [index, blocks] : specs) {
      throwIfStopped(options_.stopRequested, file.path());
      pieces.emplace_back(index, blocks, file.path());
      buildPiece(file, pieces.back());
    }
    coords_ = {};
    local_ = {};
    for (const FieldStepCount& f : fields_) readField(file, f, pieces);
    for (PieceRead& p : pieces) out.push_back(p.builder.finish());
  }

  void readCoordinates(const ExodusFile& file) {
    const size_t n = size_t(file.header().nodes);
    coords_.assign(3, std::vector<double>(n));
    file.check(ex_get_coord(file.id(), coords_[0].data(), coords_[1].data(), coords_[2].data()),
               "node coordinates");
  }

  // Connectivity is read as the file stores it (32- or 64-bit node numbers): half the memory and
  // conversion for most files, whose node numbers are 32-bit.
  void buildPiece(const ExodusFile& file, PieceRead& p) {
    if (ex_int64_status(file.id()) & EX_BULK_INT64_DB)
      buildPieceAs<int64_t>(file, p);
    else
      buildPieceAs<int32_t>(file, p);
  }

  template <class T>
  void buildPieceAs(const ExodusFile& file, PieceRead& p) {
    const ExodusHeader& h = file.header();
    std::vector<std::unique_ptr<T[]>> conn(p.blocks.size());
    std::array<uint64_t, mesh::kNumCellTypes> cells{};
    for (size_t k = 0; k < p.blocks.size(); ++k) {
      const ExodusBlock& b = h.blocks[p.blocks[k]];
      p.fileCells += uint64_t(b.elements);
      if (!b.volume || b.elements == 0) continue;
      conn[k] = localConnectivity<T>(file, b, p.nodes);
      cells[mesh::typeIndex(cellTypeOf(b))] += uint64_t(b.elements);
    }
    std::vector<glm::dvec3> points(p.nodes.size());
    for (size_t i = 0; i < points.size(); ++i) {
      const size_t n = size_t(p.nodes[i]);
      points[i] = {coords_[0][n], coords_[1][n], coords_[2][n]};
      local_[n] = kUnused;  // ready for the next piece
    }
    p.builder.setPoints(std::move(points));
    if (options_.cellOrigins)
      p.builder.keepCellOrigins(p.fileCells);
    else
      p.builder.setFileCells(p.fileCells);
    p.builder.setTimeValues(h.times);
    p.builder.setCellArrays(h.elemVars);
    for (mesh::CellType t : mesh::kAllCellTypes) p.builder.reserveCells(t, cells[typeIndex(t)]);
    uint64_t fileCell = 0;
    for (size_t k = 0; k < p.blocks.size(); ++k)
      addCells<T>(file, h.blocks[p.blocks[k]], conn[k].get(), fileCell, p);
  }

  static mesh::CellType cellTypeOf(const ExodusBlock& b) {
    switch (b.corners) {
      case 4:
        return mesh::CellType::Tet;
      case 5:
        return mesh::CellType::Pyramid;
      case 6:
        return mesh::CellType::Wedge;
      default:
        return mesh::CellType::Hex;
    }
  }

  // The block's connectivity with file node numbers (1-based) replaced by the piece's points,
  // which `nodes` gains as they are first used.
  template <class T>
  std::unique_ptr<T[]> localConnectivity(const ExodusFile& file, const ExodusBlock& b,
                                         std::vector<int64_t>& nodes) {
    const size_t n = size_t(b.elements * b.nodesPerElement);
    std::unique_ptr<T[]> conn(new T[n]);  // filled by the library: not zeroed first
    const int mode = ex_int64_status(file.id());
    ex_set_int64_status(file.id(),
                        sizeof(T) == 8 ? mode | EX_BULK_INT64_API : mode & ~EX_BULK_INT64_API);
    const int rc = ex_get_elem_conn(file.id(), b.id, conn.get());
    ex_set_int64_status(file.id(), mode);
    file.check(rc, b.place() + " connectivity");
    const int64_t numNodes = file.header().nodes;
    for (size_t i = 0; i < n; ++i) {
      const int64_t node = conn[i];
      if (node < 1 || node > numNodes)
        throw FileError(file.path(), b.place(), ": element ", i / size_t(b.nodesPerElement) + 1,
                        " refers to node ", node, " but the file has nodes 1 to ", numNodes);
      uint32_t& l = local_[size_t(node - 1)];
      if (l == kUnused) {
        l = uint32_t(nodes.size());
        nodes.push_back(node - 1);
      }
      conn[i] = T(l);
    }
    return conn;
  }

  template <class T>
  void addCells(const ExodusFile& file, const ExodusBlock& b, const T* conn, uint64_t& fileCell,
                PieceRead& p) {
    if (b.elements == 0) return;
    if (!b.volume) {
      log::info(file.path(), ": ", b.place(), " holds ", b.elements, " elements of type '", b.type,
                "', not volume elements: skipped");
      for (int64_t e = 0; e < b.elements; ++e) p.builder.addVtkCell(b.vtkType, {}, fileCell++);
      return;
    }
    const size_t npe = size_t(b.nodesPerElement);
    const int vtkType = npe == size_t(b.corners) ? linearVtkType(b.vtkType) : b.vtkType;
    // An Exodus wedge's first triangle faces the second (positive Jacobian), a VTK wedge's faces
    // away from it: without the swap every well-made wedge would count as inverted.
    const bool wedge = b.corners == 6;
    int64_t ids[kMaxNodesPerElement];
    for (size_t e = 0; e < size_t(b.elements); ++e) {
      std::copy(conn + e * npe, conn + (e + 1) * npe, ids);
      if (wedge) {
        std::swap(ids[1], ids[2]);
        std::swap(ids[4], ids[5]);
      }
      p.builder.addVtkCell(vtkType, std::span<const int64_t>(ids, npe), fileCell++, p.index);
    }
  }

  // options.step: that step alone (a field with fewer: its last), as the field's step 0.
  std::vector<uint64_t> stepsToRead(uint64_t steps) const {
    if (options_.step) return {std::min(*options_.step, steps - 1)};
    std::vector<uint64_t> all(steps);
    for (uint64_t s = 0; s < steps; ++s) all[s] = s;
    return all;
  }

  void readField(const ExodusFile& file, const FieldStepCount& f, std::vector<PieceRead>& pieces) {
    const ExodusHeader& h = file.header();
    const std::vector<std::string>& names = f.cellData ? h.elemVars : h.nodalVars;
    const size_t var = size_t(std::find(names.begin(), names.end(), f.name) - names.begin());
    if (var == names.size()) throw FileError(file.path(), "has no variable '", f.name, "'");
    const std::vector<uint64_t> steps = stepsToRead(f.steps);
    for (size_t k = 0; k < steps.size(); ++k) {
      throwIfStopped(options_.stopRequested, file.path());
      const std::string what =
          concat(f.cellData ? "element" : "nodal", " variable '", f.name, "' step ", steps[k] + 1);
      if (f.cellData)
        readElementStep(file, int(var), steps[k], k, f.name, what, pieces);
      else
        readNodalStep(file, int(var), steps[k], k, f.name, what, pieces);
    }
  }

  void readNodalStep(const ExodusFile& file, int var, uint64_t step, uint64_t asStep,
                     const std::string& name, const std::string& what,
                     std::vector<PieceRead>& pieces) {
    const ExodusHeader& h = file.header();
    std::vector<double> all(size_t(h.nodes));
    if (h.nodes > 0)
      file.check(ex_get_nodal_var(file.id(), int(step) + 1, var + 1, h.nodes, all.data()), what);
    for (PieceRead& p : pieces) {
      std::vector<float> values(p.nodes.size());
      for (size_t i = 0; i < values.size(); ++i) values[i] = float(all[size_t(p.nodes[i])]);
      p.builder.addFieldStep(name, asStep, std::move(values));
    }
  }

  // A variable the truth table leaves off a block is NaN there: those cells render transparent.
  void readElementStep(const ExodusFile& file, int var, uint64_t step, uint64_t asStep,
                       const std::string& name, const std::string& what,
                       std::vector<PieceRead>& pieces) {
    const ExodusHeader& h = file.header();
    std::vector<double> buffer;
    for (PieceRead& p : pieces) {
      std::vector<float> perCell(p.fileCells, std::numeric_limits<float>::quiet_NaN());
      size_t first = 0;
      for (size_t bi : p.blocks) {
        const ExodusBlock& b = h.blocks[bi];
        const size_t n = size_t(b.elements);
        if (n > 0 && h.truth[bi * h.elemVars.size() + size_t(var)]) {
          buffer.resize(n);
          file.check(
              ex_get_elem_var(file.id(), int(step) + 1, var + 1, b.id, b.elements, buffer.data()),
              concat(b.place(), ": ", what));
          for (size_t e = 0; e < n; ++e) perCell[first + e] = float(buffer[e]);
        }
        first += n;
      }
      p.builder.addCellFieldStep(name, asStep, perCell);
    }
  }

  const std::string& path_;
  const ReadOptions& options_;
  PiecedLayout layout_;
  std::vector<FieldStepCount> fields_;
  std::vector<std::vector<double>> coords_;
  std::vector<uint32_t> local_;  // the current piece's point of each file node, or kUnused
};

}  // namespace

mesh::UnstructuredMesh readExodus(const std::string& path, const ReadOptions& options) {
  return ExodusReader(path, options).read();
}

}  // namespace sm::io
