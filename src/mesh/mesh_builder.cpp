#include "mesh/mesh_builder.h"

#include <algorithm>
#include <cmath>

#include "common/check.h"
#include "common/error.h"
#include "common/log.h"
#include "mesh/element_geometry.h"

namespace sm::mesh {
namespace {

enum class Kind { Volume, Surface, LineOrVertex, Polyhedron, Other };

struct VtkTypeInfo {
  Kind kind;
  CellType type;     // for Volume
  uint32_t minIds;   // ids the cell must have
  bool higherOrder;  // reduced to corners
  bool voxel;        // VTK_VOXEL vertex order
};

VtkTypeInfo classify(int vtkType) {
  auto vol = [](CellType t, uint32_t n, bool ho) {
    return VtkTypeInfo{Kind::Volume, t, n, ho, false};
  };
  switch (vtkType) {
    case 10:
      return vol(CellType::Tet, 4, false);
    case 12:
      return vol(CellType::Hex, 8, false);
    case 13:
      return vol(CellType::Wedge, 6, false);
    case 14:
      return vol(CellType::Pyramid, 5, false);
    case 11:
      return VtkTypeInfo{Kind::Volume, CellType::Hex, 8, false, true};
    case 24:
      return vol(CellType::Tet, 10, true);  // quadratic tet
    case 71:
    case 78:
      return vol(CellType::Tet, 4, true);  // Lagrange/Bezier tet of any order, order 1 included
    case 25:
      return vol(CellType::Hex, 20, true);
    case 29:
      return vol(CellType::Hex, 27, true);
    case 33:
      return vol(CellType::Hex, 24, true);
    case 72:
    case 79:
      return vol(CellType::Hex, 8, true);
    case 26:
      return vol(CellType::Wedge, 15, true);
    case 31:
      return vol(CellType::Wedge, 12, true);
    case 32:
      return vol(CellType::Wedge, 18, true);
    case 73:
    case 80:
      return vol(CellType::Wedge, 6, true);
    case 27:
      return vol(CellType::Pyramid, 13, true);
    case 37:
      return vol(CellType::Pyramid, 19, true);
    case 74:
    case 81:
      return vol(CellType::Pyramid, 5, true);
    case 5:
    case 6:
    case 7:
    case 8:
    case 9:
    case 22:
    case 23:
    case 28:
    case 30:
    case 34:
    case 36:
    case 69:
    case 70:
    case 76:
    case 77:
      return {Kind::Surface, CellType::Tet, 0, false, false};
    case 1:
    case 2:
    case 3:
    case 4:
    case 21:
    case 35:
    case 68:
    case 75:
      return {Kind::LineOrVertex, CellType::Tet, 0, false, false};
    case 42:
      return {Kind::Polyhedron, CellType::Tet, 0, false, false};
    default:
      return {Kind::Other, CellType::Tet, 0, false, false};
  }
}

}  // namespace

void checkPointCount(const std::string& source, uint64_t points, std::string_view holder,
                     std::string_view fits) {
  if (points > kMaxMeshPoints)
    throw FileError(source, holder, " ", points,
                    " points: vertex ids are 32-bit, so one mesh holds at most ", kMaxMeshPoints,
                    " (", fits, ")");
}

MeshBuilder::MeshBuilder(std::string source) : source_(std::move(source)) {
  mesh_.source = source_;
}

void MeshBuilder::setPoints(std::vector<glm::dvec3> points) {
  checkPointCount(source_, points.size(), "has",
                  "split the data set into pieces, a .pvtu, and use more ranks");
  for (size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw FileError(source_, "point ", i, " has a non-finite coordinate (", p.x, ", ", p.y, ", ",
                      p.z, ")");
  }
  mesh_.points = std::move(points);
}

void MeshBuilder::reserveCells(CellType type, uint64_t n) {
  mesh_.cells[typeIndex(type)].reserve(n * numVerts(type));
  mesh_.clusters[typeIndex(type)].reserve(n);
  fileCellOf_[typeIndex(type)].reserve(n);
}

void MeshBuilder::addVtkCell(int vtkType, std::span<const int64_t> ids, uint64_t fileCell,
                             int32_t cluster) {
  VtkTypeInfo info = classify(vtkType);
  switch (info.kind) {
    case Kind::Surface:
      checkPointIds(vtkType, ids, fileCell);
      ++mesh_.skipped.surface;
      return;
    case Kind::LineOrVertex:
      checkPointIds(vtkType, ids, fileCell);
      ++mesh_.skipped.lineOrVertex;
      return;
    case Kind::Polyhedron:
      ++mesh_.skipped.polyhedra;
      return;
    case Kind::Other:
      ++mesh_.skipped.other;
      return;
    case Kind::Volume:
      break;
  }
  if (ids.size() < info.minIds)
    throw FileError(source_, "cell ", fileCell, " (VTK type ", vtkType, ") has ", ids.size(),
                    " points, expected ", info.minIds);
  // A linear cell's point count is its type's: a longer list is a damaged offset, not extra data.
  if (!info.higherOrder && ids.size() > info.minIds)
    throw FileError(source_, "cell ", fileCell, " (VTK type ", vtkType, ") has ", ids.size(),
                    " points, expected ", info.minIds);
  if (info.higherOrder) checkPointIds(vtkType, ids, fileCell);  // the dropped points too
  if (info.higherOrder && ids.size() > numVerts(info.type)) ++mesh_.skipped.quadraticReduced;
  if (info.voxel) {
    const int64_t hex[8] = {ids[0], ids[1], ids[3], ids[2], ids[4], ids[5], ids[7], ids[6]};
    addCell(CellType::Hex, hex, fileCell, cluster);
    return;
  }
  addCell(info.type, ids.first(numVerts(info.type)), fileCell, cluster);
}

void MeshBuilder::checkPointIds(int vtkType, std::span<const int64_t> ids,
                                uint64_t fileCell) const {
  for (int64_t id : ids)
    if (id < 0 || uint64_t(id) >= mesh_.points.size())
      throw FileError(source_, "cell ", fileCell, " (VTK type ", vtkType, ") refers to point ", id,
                      " but the file has ", mesh_.points.size(), " points");
}

void MeshBuilder::addCell(CellType type, std::span<const int64_t> ids, uint64_t fileCell,
                          int32_t cluster) {
  const uint32_t nv = numVerts(type);
  SM_CHECK_GE(ids.size(), nv);
  uint32_t v[8];
  for (uint32_t i = 0; i < nv; ++i) {
    if (ids[i] < 0 || uint64_t(ids[i]) >= mesh_.points.size())
      throw FileError(source_, "cell ", fileCell, " (", cellTypeName(type), ") refers to point ",
                      ids[i], " but the file has ", mesh_.points.size(), " points");
    v[i] = static_cast<uint32_t>(ids[i]);
  }
  if (hasRepeatedVertex(type, {v, nv}))
    throw FileError(source_, "cell ", fileCell, " (", cellTypeName(type),
                    ") uses the same point twice; collapsed cells are not supported");
  double vol = signedVolume(type, {v, nv}, mesh_.points);
  if (vol < 0.0) {
    mirrorElement(type, {v, nv});
    if (mesh_.invertedFixed++ == 0) firstInvertedCell_ = fileCell;
  } else if (vol == 0.0) {
    if (degenerate_++ == 0) firstDegenerateCell_ = fileCell;
  }
  auto& cells = mesh_.cells[typeIndex(type)];
  cells.insert(cells.end(), v, v + nv);
  mesh_.clusters[typeIndex(type)].push_back(cluster);
  fileCellOf_[typeIndex(type)].push_back(fileCell);
}

void MeshBuilder::addPolyhedron(const PolyhedronFaces& faces, uint64_t fileCell, int32_t cluster) {
  for (size_t f = 0; f < faces.numFaces(); ++f) {
    std::span<const uint32_t> c = faces.face(f);
    if (c.size() < 3)
      throw FileError(source_, "cell ", fileCell, " (polyhedron): face ", f, " has ", c.size(),
                      " points");
    for (size_t i = 0; i < c.size(); ++i) {
      if (c[i] >= mesh_.points.size())
        throw FileError(source_, "cell ", fileCell, " (polyhedron) refers to point ", c[i],
                        " but the file has ", mesh_.points.size(), " points");
      // (Quadratic: a longer face is refused as too large below, unchecked.)
      if (c.size() <= kMaxFacePoints &&
          std::find(c.begin() + std::ptrdiff_t(i) + 1, c.end(), c[i]) != c.end())
        throw FileError(source_, "cell ", fileCell, " (polyhedron): face ", f, " uses point ", c[i],
                        " twice");
    }
  }
  polyTets_.clear();
  const PolyhedronSplit split = tetrahedralize(faces, mesh_.points, polyTets_);
  if (split != PolyhedronSplit::Ok) {
    skipPolyhedron(fileCell, split);
    return;
  }
  ++mesh_.skipped.polyhedraSplit;
  mesh_.skipped.polyhedronTets += polyTets_.size();
  for (const auto& t : polyTets_) {
    const int64_t ids[4] = {t[0], t[1], t[2], t[3]};
    addCell(CellType::Tet, ids, fileCell, cluster);
  }
}

void MeshBuilder::skipPolyhedron(uint64_t fileCell, PolyhedronSplit why) {
  ++mesh_.skipped.polyhedra;
  // The first with a reason, even after polyhedra skipped for having no faces (the pieces of a
  // .pvtu differ there), so that the warning gives one.
  if (firstUnsplitReason_ == PolyhedronSplit::Ok) {
    firstUnsplitPolyhedron_ = fileCell;
    firstUnsplitReason_ = why;
  }
}

void MeshBuilder::addFieldStep(const std::string& name, uint64_t step, std::vector<float> values) {
  if (values.size() != mesh_.points.size())
    throw FileError(source_, "point field '", name, "' has ", values.size(), " values for ",
                    mesh_.points.size(), " points");
  Field* f = nullptr;
  for (auto& existing : mesh_.fields)
    if (existing.name == name) f = &existing;
  if (!f) {
    mesh_.fields.push_back(Field{name, {}});
    f = &mesh_.fields.back();
  }
  if (f->steps.size() <= step) f->steps.resize(step + 1);
  f->steps[step] = std::move(values);
}

void MeshBuilder::addCellFieldStep(const std::string& name, uint64_t step,
                                   std::span<const float> perFileCell) {
  auto it = std::find_if(mesh_.cellFields.begin(), mesh_.cellFields.end(),
                         [&](const CellField& f) { return f.name == name; });
  if (it == mesh_.cellFields.end()) {
    mesh_.cellFields.push_back({name, {}});
    it = mesh_.cellFields.end() - 1;
  }
  if (it->steps.size() <= step) it->steps.resize(step + 1);
  for (int t = 0; t < kNumCellTypes; ++t) {
    auto& values = it->steps[step][t];
    values.reserve(fileCellOf_[t].size());
    for (uint64_t fileCell : fileCellOf_[t]) {
      SM_CHECK_LT(fileCell, perFileCell.size());
      values.push_back(perFileCell[fileCell]);
    }
  }
}

void MeshBuilder::setClusterIds(std::span<const int64_t> perFileCell,
                                const std::string& arrayName) {
  for (int t = 0; t < kNumCellTypes; ++t) {
    auto& clusters = mesh_.clusters[t];
    const auto& fileCells = fileCellOf_[t];
    for (size_t i = 0; i < fileCells.size(); ++i) {
      uint64_t c = fileCells[i];
      if (c >= perFileCell.size())
        throw FileError(source_, "cell array '", arrayName, "' has ", perFileCell.size(),
                        " values but the file has more cells");
      int64_t id = perFileCell[c];
      if (id < 0 || id > 0x7FFFFFFF)
        throw FileError(source_, "cell array '", arrayName, "' gives cell ", c, " the cluster id ",
                        id, " (ids must be in 0 .. 2^31 - 1)");
      clusters[i] = static_cast<int32_t>(id);
    }
  }
  renumberSparseClusters(arrayName);
}

// Ids far above the cell count (a solver's rank numbers, say 2^31 - 1) would make everything that
// keeps one entry per cluster (ranks' shares, cluster statistics, one piece per cluster) allocate
// by the largest id: such ids are renumbered 0 .. k-1 in increasing order, which keeps the grouping
// and the order; a file's small ids are kept as they are.
void MeshBuilder::renumberSparseClusters(const std::string& arrayName) {
  uint64_t cells = 0;
  int32_t largest = -1;
  for (const auto& c : mesh_.clusters) {
    cells += c.size();
    for (int32_t id : c) largest = std::max(largest, id);
  }
  if (uint64_t(largest) <= cells + 4096) return;
  std::vector<int32_t> ids;
  for (const auto& c : mesh_.clusters) ids.insert(ids.end(), c.begin(), c.end());
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  for (auto& c : mesh_.clusters)
    for (int32_t& id : c) id = int32_t(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin());
  log::info(source_, ": cell array '", arrayName, "' numbers its ", ids.size(), " clusters up to ",
            largest, "; renumbered 0 .. ", ids.size() - 1, " in the same order");
}

void MeshBuilder::keepCellOrigins(uint64_t fileCells) {
  // Origins are 32-bit, like vertex ids: one rank's pieces never hold more cells.
  if (fileCells > 0xFFFFFFFFull)
    throw FileError(source_, "has ", fileCells, " cells: cell origins are 32-bit, so at most ",
                    0xFFFFFFFFull,
                    " can be kept (split it into pieces, a .pvtu, and use more ranks)");
  fileCells_ = fileCells;
  keepOrigins_ = true;
}

void MeshBuilder::setFileCells(uint64_t fileCells) {
  if (fileCells <= 0xFFFFFFFFull && !fileCells_) fileCells_ = fileCells;
}

UnstructuredMesh MeshBuilder::finish() {
  if (fileCells_ && (keepOrigins_ || mesh_.skipped.polyhedraSplit > 0)) {
    mesh_.fileCells = *fileCells_;
    for (const auto& fileCells : fileCellOf_)
      for (uint64_t c : fileCells) mesh_.cellOrigin.push_back(uint32_t(c));
  }
  for (const auto& f : mesh_.fields) {
    uint64_t nonFinite = 0, firstPoint = 0, firstStep = 0;
    for (uint64_t s = 0; s < f.steps.size(); ++s) {
      if (f.steps[s].size() != mesh_.points.size())
        throw FileError(source_, "point field '", f.name, "' has no values for time step ", s);
      for (uint64_t i = 0; i < f.steps[s].size(); ++i) {
        if (!std::isfinite(f.steps[s][i]) && nonFinite++ == 0) {
          firstPoint = i;
          firstStep = s;
        }
      }
    }
    if (nonFinite)
      log::warning(source_, ": field '", f.name, "' has ", nonFinite,
                   " non-finite values (first: point ", firstPoint, ", step ", firstStep,
                   "); they render transparent");
  }
  if (mesh_.invertedFixed)
    log::warning(source_, ": fixed the vertex order of ", mesh_.invertedFixed,
                 " inverted cells (first: cell ", firstInvertedCell_, ")");
  if (degenerate_)
    log::warning(source_, ": ", degenerate_, " cells have zero volume (first: cell ",
                 firstDegenerateCell_, ")");
  const auto& s = mesh_.skipped;
  if (s.surface)
    log::warning(source_, ": skipped ", s.surface, " 2D cells (triangles, quads, polygons)");
  if (s.lineOrVertex) log::warning(source_, ": skipped ", s.lineOrVertex, " vertex and line cells");
  if (s.polyhedraSplit)
    log::info(source_, ": split ", s.polyhedraSplit, " polyhedron cells into ", s.polyhedronTets,
              " tetrahedra");
  if (s.polyhedra && firstUnsplitReason_ != PolyhedronSplit::Ok)
    log::warning(source_, ": skipped ", s.polyhedra,
                 " polyhedron cells that cannot be split into tetrahedra on their own vertices "
                 "(first: cell ",
                 firstUnsplitPolyhedron_, ": ", describe(firstUnsplitReason_), ")");
  else if (s.polyhedra)
    log::warning(source_, ": skipped ", s.polyhedra, " polyhedron cells (the file gives no faces)");
  if (s.other) log::warning(source_, ": skipped ", s.other, " cells of unsupported types");
  if (s.quadraticReduced)
    log::warning(source_, ": reduced ", s.quadraticReduced,
                 " quadratic or higher-order cells to their corner vertices");
  return std::move(mesh_);
}

}  // namespace sm::mesh
