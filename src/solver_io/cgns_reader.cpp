// CGNS reader (docs/FORMATS.md, CGNS): each 3D zone a piece, read with libcgns in bulk, section by
// section; the zones read are welded as a .pvtu's pieces are.
#include <cgnslib.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/log.h"
#include "io_core/read_stop.h"
#include "io_core/weld.h"
#include "mesh/mesh_builder.h"
#include "solver_io/cgns_layout.h"

namespace sm::io {
namespace {

using cgns::File;
using cgns::Zone;

enum class Dim { Volume, Surface, Line, Point, Poly };

// What an element type becomes: volume types their VTK type (linear, or Lagrange for higher-order
// ones: CGNS lists the corners first, in VTK's linear order, so the builder keeps the first ones).
struct Kind {
  Dim dim;
  int vtkType;
};

Kind kindOf(ElementType_t t) {
  switch (t) {
    case TETRA_4:
      return {Dim::Volume, 10};
    case PYRA_5:
      return {Dim::Volume, 14};
    case PENTA_6:
      return {Dim::Volume, 13};
    case HEXA_8:
      return {Dim::Volume, 12};
    case TETRA_10:
    case TETRA_16:
    case TETRA_20:
    case TETRA_22:
    case TETRA_34:
    case TETRA_35:
      return {Dim::Volume, 71};
    case PYRA_13:
    case PYRA_14:
    case PYRA_21:
    case PYRA_29:
    case PYRA_30:
    case PYRA_P4_29:
    case PYRA_50:
    case PYRA_55:
      return {Dim::Volume, 74};
    case PENTA_15:
    case PENTA_18:
    case PENTA_24:
    case PENTA_38:
    case PENTA_40:
    case PENTA_33:
    case PENTA_66:
    case PENTA_75:
      return {Dim::Volume, 73};
    case HEXA_20:
    case HEXA_27:
    case HEXA_32:
    case HEXA_56:
    case HEXA_64:
    case HEXA_44:
    case HEXA_98:
    case HEXA_125:
      return {Dim::Volume, 72};
    case TRI_3:
    case TRI_6:
    case TRI_9:
    case TRI_10:
    case TRI_12:
    case TRI_15:
    case QUAD_4:
    case QUAD_8:
    case QUAD_9:
    case QUAD_12:
    case QUAD_16:
    case QUAD_P4_16:
    case QUAD_25:
      return {Dim::Surface, 5};
    case BAR_2:
    case BAR_3:
    case BAR_4:
    case BAR_5:
      return {Dim::Line, 3};
    case NODE:
      return {Dim::Point, 1};
    case NGON_n:
      return {Dim::Surface, 7};
    case NFACE_n:
      return {Dim::Poly, 42};
    default:
      return {Dim::Point, 0};
  }
}

struct Section {
  int index = 0;
  std::string name;
  ElementType_t type{};
  int64_t start = 0, end = 0;
  uint64_t count() const { return uint64_t(end - start + 1); }
};

// A section's connectivity: fixed types npe ids per element, MIXED, NGON_n and NFACE_n with
// offsets (CGNS 3.4's ElementStartOffset).
struct Connectivity {
  std::vector<cgsize_t> ids, offsets;
};

class ZoneReader {
 public:
  ZoneReader(const File& file, const Zone& zone, const cgns::Scan& scan, int piece,
             const ReadOptions& options, const std::vector<FieldStepCount>& loads)
      : f_(file),
        z_(zone),
        scan_(scan),
        piece_(piece),
        options_(options),
        loads_(loads),
        where_(zone.where()),
        b_(concat(file.path(), ", ", where_)) {}

  mesh::UnstructuredMesh read() {
    readPoints();
    if (z_.structured)
      addStructuredCells();
    else
      addSections();
    if (options_.cellOrigins)
      b_.keepCellOrigins(fileCells_);
    else
      b_.setFileCells(fileCells_);
    std::vector<std::string> cellArrays;
    for (const FieldStepCount& c : scan_.layout.fields)
      if (c.cellData) cellArrays.push_back(c.name);
    b_.setCellArrays(cellArrays);
    for (const FieldStepCount& load : loads_) addField(load);
    b_.setTimeValues(scan_.layout.times);
    return b_.finish();
  }

 private:
  std::string at(const std::string& place) const { return concat(where_, " ", place); }

  // Core range of the zone's vertices or cells, as cg_coord_read and cg_field_read take it.
  void range(bool cells, cgsize_t* rmin, cgsize_t* rmax) const {
    const int n = z_.structured ? 3 : 1;
    for (int d = 0; d < n; ++d) {
      rmin[d] = 1;
      rmax[d] =
          cgsize_t(z_.structured ? z_.dims[d] - (cells ? 1 : 0) : (cells ? z_.cells : z_.vertices));
    }
  }

  void readPoints() {
    f_.checkFits(z_.vertices, 12, where_, concat(z_.vertices, " vertices"));
    cgsize_t rmin[3], rmax[3];
    range(false, rmin, rmax);
    std::vector<glm::dvec3> points(z_.vertices);
    std::vector<double> c(z_.vertices);
    const char* names[3] = {"CoordinateX", "CoordinateY", "CoordinateZ"};
    for (int d = 0; d < 3; ++d) {
      checkArraySize("GridCoordinates", names[d], z_.vertices, [&] {
        return cg_goto(f_.fn(), z_.base, "Zone_t", z_.zone, "GridCoordinates", 0, "end");
      });
      f_.check(cg_coord_read(f_.fn(), z_.base, z_.zone, names[d], RealDouble, rmin, rmax, c.data()),
               where_, concat("reading ", names[d], " (CGNS Cartesian coordinates)"));
      for (uint64_t i = 0; i < z_.vertices; ++i) points[i][d] = c[i];
    }
    b_.setPoints(std::move(points));
  }

  // The stored array must have the zone's size: libcgns reads a smaller range of a larger one
  // without a word. Rind planes make it larger legitimately; then the library's range check holds.
  template <class GoTo>
  void checkArraySize(const std::string& node, const char* name, uint64_t expected, GoTo go) {
    if (go() != CG_OK) return;  // the read names what is missing
    int n = 0;
    cg_narrays(&n);
    for (int a = 1; a <= n; ++a) {
      char found[33] = {};
      DataType_t type{};
      int dims = 0;
      cgsize_t dim[12] = {};
      if (cg_array_info(a, found, &type, &dims, dim) != CG_OK || std::string(found) != name)
        continue;
      uint64_t count = 1;
      for (int d = 0; d < dims && d < 12; ++d) count *= dim[d] < 0 ? 0 : uint64_t(dim[d]);
      int rind[6] = {};
      const bool hasRind =
          cg_rind_read(rind) == CG_OK && std::any_of(rind, rind + 6, [](int r) { return r != 0; });
      if (count != expected && !hasRind)
        throw FileError(f_.path(), where_, " ", node, " '", name, "': ", count,
                        " values, the zone has ", expected);
      return;
    }
  }

  void addStructuredCells() {
    const int64_t ni = z_.dims[0], nj = z_.dims[1], nk = z_.dims[2];
    b_.reserveCells(mesh::CellType::Hex, z_.cells);
    uint64_t cell = 0;
    for (int64_t k = 0; k + 1 < nk; ++k) {
      for (int64_t j = 0; j + 1 < nj; ++j)
        for (int64_t i = 0; i + 1 < ni; ++i, ++cell) {
          const int64_t v = i + ni * (j + nj * k), di = 1, dj = ni, dk = ni * nj;
          const int64_t ids[8] = {v,      v + di,      v + di + dj,      v + dj,
                                  v + dk, v + di + dk, v + di + dj + dk, v + dj + dk};
          b_.addCell(mesh::CellType::Hex, ids, cell, piece_);
        }
      if (k % 64 == 0) throwIfStopped(options_.stopRequested, f_.path());
    }
    fileCells_ = z_.cells;
    volumeCells_.assign(1, {0, z_.cells});
  }

  std::vector<Section> sections() {
    int n = 0;
    f_.check(cg_nsections(f_.fn(), z_.base, z_.zone, &n), where_, "counting sections");
    std::vector<Section> out;
    for (int s = 1; s <= n; ++s) {
      Section sec;
      sec.index = s;
      char name[33] = {};
      cgsize_t start = 0, end = 0;
      int nbndry = 0, parent = 0;
      f_.check(cg_section_read(f_.fn(), z_.base, z_.zone, s, name, &sec.type, &start, &end, &nbndry,
                               &parent),
               where_, concat("reading section ", s));
      sec.name = name;
      sec.start = start;
      sec.end = end;
      if (start < 1 || end < start)
        throw FileError(f_.path(), at(concat("section '", name, "'")), ": element range ", start,
                        " to ", end);
      out.push_back(sec);
    }
    // Elements are numbered across sections; file cells (and CellCenter values) follow numbers.
    std::sort(out.begin(), out.end(),
              [](const Section& a, const Section& b) { return a.start < b.start; });
    for (size_t s = 1; s < out.size(); ++s)
      if (out[s].start <= out[s - 1].end)
        throw FileError(f_.path(), at(concat("section '", out[s].name, "'")), ": elements ",
                        out[s].start, " to ", out[s].end, " overlap section '", out[s - 1].name,
                        "' (", out[s - 1].start, " to ", out[s - 1].end, ")");
    return out;
  }

  Connectivity readSection(const Section& s) {
    const std::string place = at(concat("section '", s.name, "'"));
    cgsize_t size = 0;
    f_.check(cg_ElementDataSize(f_.fn(), z_.base, z_.zone, s.index, &size), place, "data size");
    if (size < 0) throw FileError(f_.path(), place, ": ", size, " connectivity values");
    f_.checkFits(uint64_t(size), sizeof(cgsize_t), place, "its connectivity");
    f_.checkFits(s.count(), 1, place, concat(s.count(), " elements"));
    Connectivity c;
    c.ids.resize(size_t(size));
    int npe = 0;
    cg_npe(s.type, &npe);
    if (npe > 0) {
      if (uint64_t(size) != s.count() * uint64_t(npe))
        throw FileError(f_.path(), place, ": ", size, " connectivity values for ", s.count(), " ",
                        cg_ElementTypeName(s.type), " elements");
      f_.check(cg_elements_read(f_.fn(), z_.base, z_.zone, s.index, c.ids.data(), nullptr), place,
               "reading elements");
      return c;
    }
    c.offsets.resize(s.count() + 1);
    f_.check(cg_poly_elements_read(f_.fn(), z_.base, z_.zone, s.index, c.ids.data(),
                                   c.offsets.data(), nullptr),
             place, "reading elements");
    if (c.offsets[0] != 0 || c.offsets.back() != size)
      throw FileError(f_.path(), place, ": element offsets run from ", c.offsets[0], " to ",
                      c.offsets.back(), ", not 0 to ", size);
    for (size_t e = 0; e + 1 < c.offsets.size(); ++e)
      if (c.offsets[e + 1] <= c.offsets[e])
        throw FileError(f_.path(), place, ": element ", s.start + int64_t(e), " has ",
                        c.offsets[e + 1] - c.offsets[e], " values");
    return c;
  }

  // Vertex ids, 1-based, must name the zone's vertices (face ids of NFACE_n are checked apart).
  void checkVertexIds(const Section& s, const Connectivity& c) {
    const std::string place = at(concat("section '", s.name, "'"));
    if (s.type == MIXED)  // each element's type code, then its vertices
      for (uint64_t e = 0; e < s.count(); ++e) {
        const size_t pos = size_t(c.offsets[e]), n = size_t(c.offsets[e + 1]) - pos - 1;
        const auto t = ElementType_t(c.ids[pos]);
        int npe = 0;
        if (t < NODE || t == MIXED || t == NGON_n || t == NFACE_n || t > HEXA_125 ||
            cg_npe(t, &npe) != CG_OK || npe <= 0 || size_t(npe) != n)
          throw FileError(f_.path(), place, ": element ", s.start + int64_t(e), " has type code ",
                          c.ids[pos], " and ", n, " vertices");
        checkIds(place, c.ids.data() + pos + 1, n);
      }
    else
      checkIds(place, c.ids.data(), c.ids.size());
  }

  void checkIds(const std::string& place, const cgsize_t* ids, size_t n) const {
    for (size_t i = 0; i < n; ++i)
      if (ids[i] < 1 || uint64_t(ids[i]) > z_.vertices)
        throw FileError(f_.path(), place, ": an element refers to vertex ", ids[i],
                        " but the zone has ", z_.vertices, " (1 to ", z_.vertices, ")");
  }

  void addSections() {
    const std::vector<Section> all = sections();
    for (const Section& s : all)
      if (s.type == NGON_n &&
          std::any_of(all.begin(), all.end(), [](const Section& t) { return t.type == NFACE_n; })) {
        faces_.push_back({s, readSection(s)});
        checkVertexIds(s, faces_.back().second);
      }
    for (const Section& s : all) {
      throwIfStopped(options_.stopRequested, f_.path());
      const Kind kind = kindOf(s.type);
      if (s.type == NGON_n) {
        if (faces_.empty())
          log::info(f_.path(), ": ", at(concat("section '", s.name, "'")), ": ", s.count(),
                    " NGON_n faces with no NFACE_n cells: skipped");
        fileCells_ += s.count();  // faces, not cells: neither kept nor counted as skipped
        continue;
      }
      if (kind.vtkType == 0 && s.type != MIXED)
        throw FileError(f_.path(), at(concat("section '", s.name, "'")), ": element type ",
                        cg_ElementTypeName(s.type), " is not supported");
      Connectivity c = readSection(s);
      if (s.type == NFACE_n)
        addPolyhedra(s, c);
      else
        addElements(s, c);
    }
    uint64_t volume = 0;
    for (const auto& [first, count] : volumeCells_) volume += count;
    if (volume != z_.cells)
      log::info(f_.path(), ": ", where_, " declares ", z_.cells, " cells; its sections hold ",
                volume, " volume elements");
  }

  void addElements(const Section& s, const Connectivity& c) {
    checkVertexIds(s, c);
    int npe = 0;
    cg_npe(s.type, &npe);
    std::vector<int64_t> ids(64);
    uint64_t surface = 0;
    const uint64_t first = fileCells_;
    for (uint64_t e = 0; e < s.count(); ++e) {
      ElementType_t type = s.type;
      size_t pos = npe > 0 ? e * size_t(npe) : size_t(c.offsets[e]);
      size_t n = npe > 0 ? size_t(npe) : size_t(c.offsets[e + 1] - c.offsets[e]);
      if (npe <= 0) type = ElementType_t(c.ids[pos++]), --n;
      const Kind kind = kindOf(type);
      if (kind.dim != Dim::Volume) {
        b_.addVtkCell(kind.vtkType, {}, first + e, piece_);  // ids checked above
        ++surface;
        continue;
      }
      ids.resize(n);
      for (size_t k = 0; k < n; ++k) ids[k] = c.ids[pos + k] - 1;
      // A CGNS pentahedron's first triangle faces the second (SIDS: face N1 N3 N2 points out), a
      // VTK wedge's faces away from it: turned, well-made wedges are not reported as inverted.
      if (kind.vtkType == 13 || kind.vtkType == 73) {
        std::swap(ids[1], ids[2]);
        std::swap(ids[4], ids[5]);
      }
      b_.addVtkCell(kind.vtkType, ids, first + e, piece_);
      addVolumeCell(first + e);
    }
    fileCells_ += s.count();
    if (surface > 0)
      log::info(f_.path(), ": ", at(concat("section '", s.name, "'")), ": ", surface, " ",
                cg_ElementTypeName(s.type),
                " elements that are not volume cells (boundary "
                "faces, edges): skipped");
  }

  // Volume elements in number order: the order of a zone's CellCenter values.
  void addVolumeCell(uint64_t fileCell) {
    if (!volumeCells_.empty() && volumeCells_.back().first + volumeCells_.back().second == fileCell)
      ++volumeCells_.back().second;
    else
      volumeCells_.push_back({fileCell, 1});
  }

  // NFACE_n: signed numbers of NGON_n elements, negative where the face points into the cell.
  void addPolyhedra(const Section& s, const Connectivity& c) {
    mesh::PolyhedronFaces poly;
    for (uint64_t e = 0; e < s.count(); ++e) {
      poly.ids.clear();
      poly.offsets.assign(1, 0);
      for (cgsize_t k = c.offsets[e]; k < c.offsets[e + 1]; ++k) {
        const cgsize_t signedFace = c.ids[size_t(k)];
        const int64_t face = std::abs(int64_t(signedFace));
        const auto* ngon = faceSection(face);
        if (!ngon)
          throw FileError(f_.path(), at(concat("section '", s.name, "'")), ": element ",
                          s.start + int64_t(e), " refers to face ", signedFace,
                          ", which no NGON_n section of the zone holds");
        const Connectivity& fc = ngon->second;
        const size_t i = size_t(face - ngon->first.start);
        const size_t from = poly.ids.size();
        for (cgsize_t v = fc.offsets[i]; v < fc.offsets[i + 1]; ++v)
          poly.ids.push_back(uint32_t(fc.ids[size_t(v)] - 1));
        if (signedFace < 0) std::reverse(poly.ids.begin() + std::ptrdiff_t(from), poly.ids.end());
        poly.offsets.push_back(uint32_t(poly.ids.size()));
      }
      b_.addPolyhedron(poly, fileCells_ + e, piece_);
      addVolumeCell(fileCells_ + e);
    }
    fileCells_ += s.count();
  }

  const std::pair<Section, Connectivity>* faceSection(int64_t face) const {
    for (const auto& f : faces_)
      if (face >= f.first.start && face <= f.first.end) return &f;
    return nullptr;
  }

  // The solution that holds step `step` of `name` at this location, or null.
  const cgns::Solution* solutionOf(const std::string& name, bool cellData, uint64_t step) const {
    uint64_t k = 0;
    for (const cgns::Solution& s : cellData ? z_.cellSolutions : z_.vertexSolutions)
      if (std::find(s.fields.begin(), s.fields.end(), name) != s.fields.end() && k++ == step)
        return &s;
    return nullptr;
  }

  void addField(const FieldStepCount& load) {
    const uint64_t first = options_.step ? std::min(*options_.step, load.steps - 1) : 0;
    const uint64_t last = options_.step ? first : load.steps - 1;
    for (uint64_t step = first; step <= last; ++step) {
      throwIfStopped(options_.stopRequested, f_.path());
      std::vector<float> values = readValues(load, step);
      const uint64_t outStep = step - first;
      if (!load.cellData) {
        b_.addFieldStep(load.name, outStep, std::move(values));
        continue;
      }
      std::vector<float> perFileCell(fileCells_, std::numeric_limits<float>::quiet_NaN());
      uint64_t k = 0;
      for (const auto& [cell, count] : volumeCells_)
        for (uint64_t i = 0; i < count && k < values.size(); ++i)
          perFileCell[cell + i] = values[k++];
      b_.addCellFieldStep(load.name, outStep, perFileCell);
    }
  }

  std::vector<float> readValues(const FieldStepCount& load, uint64_t step) {
    const uint64_t n = load.cellData ? z_.cells : z_.vertices;
    const cgns::Solution* sol = solutionOf(load.name, load.cellData, step);
    if (!sol) {
      if (log::firstTime(concat("cgns-missing ", f_.path(), where_, load.name)))
        log::warning(f_.path(), ": ", where_, " has no step ", step, " of field '", load.name,
                     "' that other zones have: its points render transparent");
      return std::vector<float>(load.cellData ? fileCells_ : z_.vertices,
                                std::numeric_limits<float>::quiet_NaN());
    }
    const std::string place = concat("solution '", sol->name, "'");
    checkArraySize(place, load.name.c_str(), n, [&] {
      return cg_goto(f_.fn(), z_.base, "Zone_t", z_.zone, "FlowSolution_t", sol->index, "end");
    });
    if (load.cellData) {
      uint64_t volume = 0;
      for (const auto& [cell, count] : volumeCells_) volume += count;
      if (volume != n)
        throw FileError(f_.path(), at(place), " field '", load.name, "': ", n,
                        " CellCenter values (the zone's cells) for ", volume, " volume elements");
    }
    f_.checkFits(n, 4, at(place), concat("field '", load.name, "'"));
    std::vector<float> values(n);
    cgsize_t rmin[3], rmax[3];
    range(load.cellData, rmin, rmax);
    f_.check(cg_field_read(f_.fn(), z_.base, z_.zone, sol->index, load.name.c_str(), RealSingle,
                           rmin, rmax, values.data()),
             at(place), concat("reading field '", load.name, "'"));
    return values;
  }

  const File& f_;
  const Zone& z_;
  const cgns::Scan& scan_;
  const int piece_;
  const ReadOptions& options_;
  const std::vector<FieldStepCount>& loads_;
  const std::string where_;
  mesh::MeshBuilder b_;
  uint64_t fileCells_ = 0;
  std::vector<std::pair<uint64_t, uint64_t>> volumeCells_;  // (first file cell, count) runs
  std::vector<std::pair<Section, Connectivity>> faces_;     // NGON_n sections, for NFACE_n
};

}  // namespace

mesh::UnstructuredMesh readCgns(const std::string& path, const ReadOptions& options) {
  File file(path);
  const cgns::Scan scan = cgns::scan(file);
  const std::vector<int> pieces = choosePieces(path, scan.zones.size(), options);
  const std::vector<FieldStepCount> loads = piecedFieldSteps(path, scan.layout, options);
  std::vector<mesh::UnstructuredMesh> meshes;
  for (int piece : pieces) {
    throwIfStopped(options.stopRequested, path);
    meshes.push_back(
        ZoneReader(file, scan.zones[size_t(piece)], scan, piece, options, loads).read());
  }
  mesh::UnstructuredMesh m = weldPieces(path, std::move(meshes));
  // Zones of 2D bases are surfaces: counted once, with the first piece.
  if (scan.skippedZones > 0 && !pieces.empty() && pieces.front() == 0) {
    log::info(path, ": ", scan.skippedZones, " zones of 2D (or 1D) bases skipped (",
              scan.skippedCells, " cells)");
    m.skipped.surface += scan.skippedCells;
  }
  return m;
}

}  // namespace sm::io
