// Gmsh .msh 4.1 files (docs/FORMATS.md): the sections are parsed by gmsh_sections.cpp; here they
// become pieces (a partitioned file's partitions, else the whole file), points, cells and fields.
// Node and element tags may be sparse: they are mapped to dense indices. Gmsh's vertex order is
// VTK's for the corners of tetrahedra, hexahedra and pyramids (prisms are mirrored), and
// higher-order elements list their corners first, so cells go to the builder as their linear VTK
// type.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "common/error.h"
#include "io_core/array_plan.h"
#include "io_core/weld.h"
#include "mesh/mesh_builder.h"
#include "solver_io/gmsh_sections.h"
#include "solver_io/pieced_readers.h"

namespace sm::io {
namespace {

// Gmsh's prism has its first triangle wound towards the second; VTK's wedge away from it.
constexpr int kWedge = 13;
constexpr uint32_t kPrismToVtk[6] = {0, 2, 1, 3, 5, 4};

// Tag -> dense index: a table when tags are about as many as the entries, else a sorted list.
class TagIndex {
 public:
  // Returns the first tag given twice, or 0.
  uint64_t build(const std::vector<uint64_t>& tags) {
    if (tags.empty()) return 0;
    const auto [lo, hi] = std::minmax_element(tags.begin(), tags.end());
    min_ = *lo;
    if (*hi - *lo < 4 * tags.size() + 1024) {
      table_.assign(*hi - *lo + 1, -1);
      for (size_t i = 0; i < tags.size(); ++i) {
        int64_t& slot = table_[tags[i] - min_];
        if (slot >= 0) return tags[i];
        slot = int64_t(i);
      }
      return 0;
    }
    sorted_.resize(tags.size());
    for (size_t i = 0; i < tags.size(); ++i) sorted_[i] = {tags[i], int64_t(i)};
    std::sort(sorted_.begin(), sorted_.end());
    for (size_t i = 1; i < sorted_.size(); ++i)
      if (sorted_[i].first == sorted_[i - 1].first) return sorted_[i].first;
    return 0;
  }
  int64_t find(uint64_t tag) const {
    if (!table_.empty()) return tag >= min_ && tag - min_ < table_.size() ? table_[tag - min_] : -1;
    auto it =
        std::lower_bound(sorted_.begin(), sorted_.end(), std::pair<uint64_t, int64_t>{tag, -1});
    return it != sorted_.end() && it->first == tag ? it->second : -1;
  }

 private:
  uint64_t min_ = 0;
  std::vector<int64_t> table_;
  std::vector<std::pair<uint64_t, int64_t>> sorted_;
};

struct FieldInfo {
  std::string name;
  bool cells = false;
  uint32_t components = 1;
  std::map<int64_t, double> steps;  // gmsh's step number -> time
};

std::vector<FieldInfo> fieldsOf(const GmshFile& f, const std::string& src) {
  std::vector<FieldInfo> out;
  for (const GmshDataSection& s : f.data) {
    auto it = std::find_if(out.begin(), out.end(), [&](const FieldInfo& i) {
      return i.name == s.name && i.cells == s.cells;
    });
    if (it == out.end()) it = out.insert(out.end(), {s.name, s.cells, s.components, {}});
    if (it->components != s.components)
      throw FileError(src, s.cells ? "$ElementData" : "$NodeData", " '", s.name, "' has ",
                      it->components, " components in one step and ", s.components, " in another");
    it->steps.emplace(s.step, s.time);
  }
  return out;
}

PiecedLayout layoutOf(const GmshFile& f, const std::vector<FieldInfo>& fields,
                      const std::string& src) {
  PiecedLayout l;
  const int pieces = std::max(f.partitions, 1);
  for (int p = 0; p < pieces; ++p)
    l.pieces.push_back(f.partitions ? concat(src, ", partition ", p + 1) : src);
  l.pieceCells.assign(pieces, 0);
  for (const GmshElementBlock& b : f.blocks)
    if (b.dim == 3) l.pieceCells[b.piece] += b.count;
  const FieldInfo* longest = nullptr;
  for (const FieldInfo& i : fields) {
    l.fields.push_back({i.name, i.steps.size(), i.cells, i.components});
    if (!longest || i.steps.size() > longest->steps.size()) longest = &i;
  }
  if (longest)
    for (const auto& [step, time] : longest->steps) l.times.push_back(time);
  l.files = {src};
  return l;
}

class GmshReader {
 public:
  GmshReader(const FileBytes& bytes, const std::string& src, const ReadOptions& options)
      : src_(src),
        options_(options),
        parser_(bytes, src, true, options.stopRequested),
        begin_(reinterpret_cast<const char*>(bytes.data())) {}

  mesh::UnstructuredMesh read() {
    file_ = parser_.parse();
    fields_ = fieldsOf(file_, src_);
    const PiecedLayout layout = layoutOf(file_, fields_, src_);
    const std::vector<int> pieces = choosePieces(src_, layout.pieces.size(), options_);
    const std::vector<FieldStepCount> loads = piecedFieldSteps(src_, layout, options_);
    if (uint64_t dup = nodeIndex_.build(file_.nodeTags))
      throw FileError(src_, "node tag ", dup, " is given twice in $Nodes");
    std::vector<uint64_t> elementTags;
    for (const GmshElementBlock& b : file_.blocks)
      elementTags.insert(elementTags.end(), b.tags.begin(), b.tags.end());
    if (uint64_t dup = elementIndex_.build(elementTags))
      throw FileError(src_, "element tag ", dup, " is given twice in $Elements");
    std::vector<mesh::UnstructuredMesh> meshes;
    for (int p : pieces) {
      throwIfStopped(options_.stopRequested, src_);
      meshes.push_back(readPiece(p, loads, layout));
    }
    // One piece needs no weld (which would copy it).
    mesh::UnstructuredMesh m =
        meshes.size() == 1 ? std::move(meshes[0]) : weldPieces(src_, std::move(meshes));
    return m;
  }

 private:
  mesh::UnstructuredMesh readPiece(int piece, const std::vector<FieldStepCount>& loads,
                                   const PiecedLayout& layout) {
    mesh::MeshBuilder b(src_);
    // Points: every node for a file of one piece; a partition's, the nodes its elements use.
    std::vector<int64_t> globalOf;  // local point -> node index
    std::vector<int64_t> localOf(file_.partitions ? file_.nodes.size() : 0, -1);
    if (!file_.partitions) {
      b.setPoints(file_.nodes);
    } else {
      for (const GmshElementBlock& blk : file_.blocks)
        if (blk.piece == piece)
          for (size_t k = 0; k < blk.corners.size(); ++k) {
            const int64_t n = node(blk, k / gmshElementType(blk.type).corners, blk.corners[k]);
            if (localOf[n] < 0) {
              localOf[n] = int64_t(globalOf.size());
              globalOf.push_back(n);
            }
          }
      std::vector<glm::dvec3> pts(globalOf.size());
      for (size_t i = 0; i < pts.size(); ++i) pts[i] = file_.nodes[globalOf[i]];
      b.setPoints(std::move(pts));
    }
    reserveCells(b, piece);
    std::vector<int64_t> cellsOf;  // file cell -> element index over all blocks
    uint64_t first = 0;
    for (const GmshElementBlock& blk : file_.blocks) {
      if (blk.piece == piece) addBlock(b, blk, first, localOf, cellsOf);
      first += blk.count;
    }
    if (options_.cellOrigins)
      b.keepCellOrigins(cellsOf.size());
    else
      b.setFileCells(cellsOf.size());
    std::vector<std::string> cellArrays;
    for (const FieldInfo& i : fields_)
      if (i.cells) cellArrays.push_back(i.name);
    b.setCellArrays(cellArrays);
    for (const FieldStepCount& load : loads) addField(b, load, globalOf, cellsOf);
    // Every step's time, also when one step is loaded (as a series keeps them): the step counts.
    b.setTimeValues(layout.times);
    mesh::UnstructuredMesh m = b.finish();
    // Reduced here rather than by the builder (which would need the other nodes as points too).
    for (const GmshElementBlock& blk : file_.blocks)
      if (blk.piece == piece && blk.dim == 3 &&
          gmshElementType(blk.type).nodes > gmshElementType(blk.type).corners)
        m.skipped.quadraticReduced += blk.count;
    return m;
  }

  void reserveCells(mesh::MeshBuilder& b, int piece) const {
    uint64_t n[4] = {0, 0, 0, 0};  // VTK types 10, 12, 13, 14
    for (const GmshElementBlock& blk : file_.blocks)
      if (blk.piece == piece && blk.dim == 3) {
        const int t = gmshElementType(blk.type).vtkType;
        n[t == 10 ? 0 : t - 11] += blk.count;
      }
    b.reserveCells(mesh::CellType::Tet, n[0]);
    b.reserveCells(mesh::CellType::Hex, n[1]);
    b.reserveCells(mesh::CellType::Wedge, n[2]);
    b.reserveCells(mesh::CellType::Pyramid, n[3]);
  }

  // Node index of corner `tag` of element e of a block.
  int64_t node(const GmshElementBlock& blk, uint64_t e, uint64_t tag) const {
    const int64_t n = nodeIndex_.find(tag);
    if (n >= 0) return n;
    const std::string what = concat("element ", blk.tags[e], " of entity ", blk.entity,
                                    " refers to node ", tag, ", which $Nodes does not have");
    if (file_.binary) throw FileError(src_, "section $Elements, entity ", blk.entity, ": ", what);
    throw FileError(src_, "line ", 1 + std::count(begin_, blk.lines[e], '\n'), ": ", what);
  }

  void addBlock(mesh::MeshBuilder& b, const GmshElementBlock& blk, uint64_t first,
                const std::vector<int64_t>& localOf, std::vector<int64_t>& cellsOf) {
    const GmshElementType t = gmshElementType(blk.type);
    int64_t ids[8];
    for (uint64_t e = 0; e < blk.count; ++e) {
      const uint64_t fileCell = cellsOf.size();
      cellsOf.push_back(int64_t(first + e));
      if (blk.dim != 3) {
        b.addVtkCell(t.vtkType, {}, fileCell, blk.piece);
        continue;
      }
      for (uint32_t k = 0; k < t.corners; ++k) {
        const uint32_t from = t.vtkType == kWedge ? kPrismToVtk[k] : k;
        const int64_t n = node(blk, e, blk.corners[e * t.corners + from]);
        ids[k] = file_.partitions ? localOf[n] : n;
      }
      b.addVtkCell(t.vtkType, {ids, t.corners}, fileCell, blk.piece);
    }
  }

  void addField(mesh::MeshBuilder& b, const FieldStepCount& load,
                const std::vector<int64_t>& globalOf, const std::vector<int64_t>& cellsOf) {
    std::string name = load.name;
    int component = -1;
    auto info = std::find_if(fields_.begin(), fields_.end(), [&](const FieldInfo& i) {
      return i.name == name && i.cells == load.cellData;
    });
    if (info == fields_.end()) {
      auto split = splitComponent(load.name);
      name = split->first;
      component = split->second;
      info = std::find_if(fields_.begin(), fields_.end(), [&](const FieldInfo& i) {
        return i.name == name && i.cells == load.cellData;
      });
    }
    std::vector<int64_t> steps;
    for (const auto& [step, time] : info->steps) steps.push_back(step);
    uint64_t from = 0, to = steps.size();
    if (options_.step) from = std::min<uint64_t>(*options_.step, to - 1), to = from + 1;
    for (uint64_t k = from; k < to; ++k) {
      const std::vector<float>& all = values(*info, steps[k], component);
      const std::vector<int64_t>& pick = info->cells ? cellsOf : globalOf;
      std::vector<float> v;
      if (!info->cells && !file_.partitions) {
        v = all;
      } else {
        v.resize(pick.size());
        for (size_t i = 0; i < pick.size(); ++i) v[i] = all[pick[i]];
      }
      if (info->cells)
        b.addCellFieldStep(load.name, k - from, v);
      else
        b.addFieldStep(load.name, k - from, std::move(v));
    }
  }

  // One step of a field over every node (or element), NaN where the file gives none; computed
  // once and kept for the other pieces.
  const std::vector<float>& values(const FieldInfo& info, int64_t step, int component) {
    auto key = std::make_tuple(info.name, info.cells, step, component);
    if (auto it = cache_.find(key); it != cache_.end()) return it->second;
    const TagIndex& index = info.cells ? elementIndex_ : nodeIndex_;
    uint64_t n = 0;
    if (info.cells)
      for (const GmshElementBlock& blk : file_.blocks) n += blk.count;
    else
      n = file_.nodes.size();
    std::vector<float> out(n, std::numeric_limits<float>::quiet_NaN());
    for (const GmshDataSection& s : file_.data) {
      if (s.name != info.name || s.cells != info.cells || s.step != step) continue;
      throwIfStopped(options_.stopRequested, src_);
      parser_.forEachValue(s, [&](int64_t tag, std::span<const double> v) {
        const int64_t i = tag < 0 ? -1 : index.find(uint64_t(tag));
        if (i < 0)
          throw FileError(src_, s.cells ? "$ElementData" : "$NodeData", " '", s.name, "' step ",
                          step, " has a value for ", s.cells ? "element " : "node ", tag,
                          ", which the mesh does not have");
        double x = 0;
        if (component >= 0)
          x = v[component];
        else if (v.size() == 1)
          x = v[0];
        else {
          for (double c : v) x += c * c;
          x = std::sqrt(x);
        }
        out[i] = float(x);
      });
    }
    return cache_[key] = std::move(out);
  }

  const std::string& src_;
  const ReadOptions& options_;
  GmshParser parser_;
  const char* begin_ = nullptr;
  GmshFile file_;
  std::vector<FieldInfo> fields_;
  TagIndex nodeIndex_, elementIndex_;
  std::map<std::tuple<std::string, bool, int64_t, int>, std::vector<float>> cache_;
};

}  // namespace

PiecedLayout gmshLayout(const FileBytes& bytes, const std::string& source) {
  GmshParser parser(bytes, source, false, {});
  const GmshFile f = parser.parse();
  return layoutOf(f, fieldsOf(f, source), source);
}

mesh::UnstructuredMesh readGmsh(const FileBytes& bytes, const std::string& source,
                                const ReadOptions& options) {
  return GmshReader(bytes, source, options).read();
}

}  // namespace sm::io
