// AFLR3/FUN3D UGRID reader. Layout (docs/FORMATS.md): the 7 counts nnodes ntri nquad ntet npyr
// nprism nhex; xyz per node; triangle and quad connectivity; one surface tag per triangle and
// quad; tetrahedra, pyramids, prisms, hexahedra (1-based node numbers). The binary variant is
// named by the suffix before .ugrid: [l]b8, [l]b4 (C stream, 32-bit ints, 64- or 32-bit reals;
// l = little-endian, else big-endian), [l]b8l (64-bit ints), [l]r8, [l]r4 (Fortran unformatted:
// a record with the counts, then one record with everything else); no suffix: ascii.
// Per-node fields come from float32 side files (<stem>.<FIELD>[.<STEP>].f32).
#include <algorithm>
#include <filesystem>

#include "common/error.h"
#include "common/file_util.h"
#include "io/readers.h"
#include "io_core/array_plan.h"
#include "io_core/numeric_array.h"
#include "io_core/text_scan.h"
#include "mesh/mesh_builder.h"

namespace sm::io {
namespace {

namespace fs = std::filesystem;
using mesh::CellType;

struct Variant {
  std::string_view suffix;
  bool ascii, fortran, bigEndian;
  int intSize, realSize;
};

constexpr Variant kVariants[] = {
    {"b8", false, false, true, 4, 8},  {"lb8", false, false, false, 4, 8},
    {"b8l", false, false, true, 8, 8}, {"lb8l", false, false, false, 8, 8},
    {"b4", false, false, true, 4, 4},  {"lb4", false, false, false, 4, 4},
    {"r8", false, true, true, 4, 8},   {"lr8", false, true, false, 4, 8},
    {"r4", false, true, true, 4, 4},   {"lr4", false, true, false, 4, 4}};
constexpr Variant kAscii{"", true, false, false, 0, 0};

// UGRID -> VTK vertex order: vtk[k] = ugrid[perm[k]]. A UGRID pyramid has its base on nodes
// 1 2 5 4 and its apex on node 3 (it is a prism with nodes 3 and 6 merged); a UGRID prism has
// triangle 1 2 3 wound towards 4 5 6, VTK's away from it. Tetrahedra and hexahedra agree.
constexpr int kPyramidToVtk[5] = {1, 0, 3, 4, 2};
constexpr int kPrismToVtk[6] = {1, 0, 2, 4, 3, 5};

struct Counts {
  uint64_t nodes, tris, quads, tets, pyrs, prisms, hexes;
  uint64_t volumeInts() const { return 4 * tets + 5 * pyrs + 6 * prisms + 8 * hexes; }
  uint64_t surfaceInts() const { return 4 * tris + 5 * quads; }  // connectivity and tags
};

// "wing.lb8.ugrid" -> (lb8 variant, "wing"); "wing.ugrid" -> (ascii, "wing").
std::pair<Variant, std::string> variantOf(const std::string& path) {
  std::string name = fs::path(path).filename().string();
  std::string stem = name.substr(0, name.size() - std::min<size_t>(name.size(), 6));  // ".ugrid"
  size_t dot = stem.rfind('.');
  if (dot != std::string::npos) {
    std::string suffix = stem.substr(dot + 1);
    std::transform(suffix.begin(), suffix.end(), suffix.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    for (const Variant& v : kVariants)
      if (v.suffix == suffix) return {v, stem.substr(0, dot)};
  }
  return {kAscii, stem};
}

class UgridReader {
 public:
  UgridReader(FileBytes& bytes, const std::string& source, const ReadOptions& options,
              bool sideFiles)
      : bytes_(bytes), src_(source), options_(options), sideFiles_(sideFiles), builder_(source) {
    std::tie(variant_, stem_) = variantOf(source);
    swap_ = needsSwap(variant_.bigEndian);
  }

  mesh::UnstructuredMesh read() {
    chooseClusterArray(src_, {},
                       options_);  // UGRID has no cell arrays: a requested one is an error
    throwIfStopped(options_.stopRequested, src_);
    if (variant_.ascii)
      readAscii();
    else
      readBinary();
    throwIfStopped(options_.stopRequested, src_);
    if (sideFiles_) readSideFields();
    throwIfStopped(options_.stopRequested, src_);
    return builder_.finish();
  }

 private:
  void checkCounts(const int64_t c[7], uint64_t maxItems) {
    static const char* names[7] = {"nodes",      "surface triangles", "surface quads",
                                   "tetrahedra", "pyramids",          "prisms",
                                   "hexahedra"};
    for (int i = 0; i < 7; ++i)
      if (c[i] < 0 || uint64_t(c[i]) > maxItems)
        throw FileError(src_, "declares ", c[i], " ", names[i], ", impossible for a file of ",
                        bytes_.size(), " bytes");
    counts_ = {uint64_t(c[0]), uint64_t(c[1]), uint64_t(c[2]), uint64_t(c[3]),
               uint64_t(c[4]), uint64_t(c[5]), uint64_t(c[6])};
    mesh::checkPointCount(src_, counts_.nodes, "declares",
                          "split it into the pieces of a .pvtu and use more ranks");
  }

  void readBinary() {
    const uint64_t is = variant_.intSize, rs = variant_.realSize;
    uint64_t pos = 0;
    if (variant_.fortran) pos = fortranMarker(pos, 7 * is, "the counts");
    if (bytes_.size() < pos + 7 * is)
      throw FileError(src_, "is too short for the 7 counts of a UGRID file");
    int64_t c[7];
    for (int i = 0; i < 7; ++i) c[i] = readInt(pos + i * is);
    checkCounts(c, bytes_.size());
    pos += 7 * is;
    const Counts& n = counts_;
    const uint64_t payload = 3 * n.nodes * rs + (n.surfaceInts() + n.volumeInts()) * is;
    if (variant_.fortran) {
      fortranMarker(pos, 7 * is, "the counts (end)");
      pos = fortranMarker(pos + 4, payload, "the grid");
    }
    if (payload > bytes_.size() - pos)
      throw FileError(src_, "declares ", n.nodes, " nodes and ",
                      n.tets + n.pyrs + n.prisms + n.hexes, " volume elements, which need ",
                      payload, " bytes; the file has ", bytes_.size() - pos);
    const uint8_t* d = bytes_.data() + pos;
    builder_.setPoints(
        toPoints(NumericArray::view(rs == 8 ? ScalarType::Float64 : ScalarType::Float32, 3, n.nodes,
                                    d, swap_),
                 options_.threads));
    d += 3 * n.nodes * rs + n.surfaceInts() * is;
    addSurfaceCells();
    if (is == 8)
      addVolumeCells([&](uint64_t i) { return loadAs<int64_t>(d + i * 8, swap_); });
    else
      addVolumeCells([&](uint64_t i) { return int64_t(loadAs<int32_t>(d + i * 4, swap_)); });
    if (variant_.fortran) fortranMarker(pos + payload, payload, "the grid (end)");
  }

  // Checks the 4-byte Fortran record marker at pos; returns the position after it.
  uint64_t fortranMarker(uint64_t pos, uint64_t expected, const char* record) {
    if (expected > 0x7FFFFFFFu)
      throw FileError(src_, "the record with ", record,
                      " is larger than 2 GiB (Fortran sub-records);"
                      " convert the grid to a C-binary variant such as .lb8.ugrid");
    if (bytes_.size() < 4 || pos > bytes_.size() - 4)
      throw FileError(src_, "the file ends before the Fortran record marker of ", record);
    uint32_t m = loadAs<uint32_t>(bytes_.data() + pos, swap_);
    if (m != expected)
      throw FileError(src_, "Fortran record marker of ", record, " is ", m, ", expected ", expected,
                      " (is this really a Fortran unformatted ", variant_.suffix, " file?)");
    return pos + 4;
  }

  int64_t readInt(uint64_t pos) const {
    const uint8_t* p = bytes_.data() + pos;
    return variant_.intSize == 8 ? loadAs<int64_t>(p, swap_) : loadAs<int32_t>(p, swap_);
  }

  void readAscii() {
    TextCursor cur(reinterpret_cast<const char*>(bytes_.data()),
                   reinterpret_cast<const char*>(bytes_.data()) + bytes_.size());
    int64_t c[7];
    for (int i = 0; i < 7; ++i) {
      std::string_view tok = cur.token();
      if (!parseNumber(tok, c[i]))
        throw FileError(src_, "is not an ascii UGRID file (count ", i, " is '", printable(tok),
                        "'); binary files need a suffix such as .lb8.ugrid or .b8.ugrid");
    }
    checkCounts(c, maxNumbersInText(cur.remaining()));
    const Counts& n = counts_;
    if (3 * n.nodes + n.surfaceInts() + n.volumeInts() > maxNumbersInText(cur.remaining()))
      throw FileError(src_, "declares more numbers than the file can hold");
    std::vector<double> xyz(3 * n.nodes);
    scanNumbers(cur, xyz.data(), xyz.size(), src_, "node coordinates");
    std::vector<glm::dvec3> pts(n.nodes);
    for (uint64_t i = 0; i < n.nodes; ++i) pts[i] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
    builder_.setPoints(std::move(pts));
    std::vector<int64_t> skip(std::min<uint64_t>(n.surfaceInts(), 1 << 16));
    for (uint64_t left = n.surfaceInts(); left > 0;) {
      uint64_t k = std::min<uint64_t>(left, skip.size());
      scanNumbers(cur, skip.data(), k, src_, "surface faces");
      left -= k;
    }
    addSurfaceCells();
    std::vector<int64_t> ids(n.volumeInts());
    scanNumbers(cur, ids.data(), ids.size(), src_, "volume elements");
    addVolumeCells([&](uint64_t i) { return ids[i]; });
  }

  // Boundary faces are 2D cells: counted as skipped, as for every format.
  void addSurfaceCells() {
    for (uint64_t i = 0; i < counts_.tris; ++i) builder_.addVtkCell(5, {}, i);
    for (uint64_t i = 0; i < counts_.quads; ++i) builder_.addVtkCell(9, {}, counts_.tris + i);
  }

  // nodeAt(i): the i-th node number of the volume element lists.
  template <class NodeAt>
  void addVolumeCells(NodeAt nodeAt) {
    const Counts& n = counts_;
    builder_.reserveCells(CellType::Tet, n.tets);
    builder_.reserveCells(CellType::Pyramid, n.pyrs);
    builder_.reserveCells(CellType::Wedge, n.prisms);
    builder_.reserveCells(CellType::Hex, n.hexes);
    static const int kIdentity[8] = {0, 1, 2, 3, 4, 5, 6, 7};
    const struct {
      CellType type;
      uint64_t count;
      const int* perm;
    } blocks[4] = {{CellType::Tet, n.tets, kIdentity},
                   {CellType::Pyramid, n.pyrs, kPyramidToVtk},
                   {CellType::Wedge, n.prisms, kPrismToVtk},
                   {CellType::Hex, n.hexes, kIdentity}};
    uint64_t pos = 0, fileCell = n.tris + n.quads;
    for (const auto& b : blocks) {
      const uint32_t nv = mesh::numVerts(b.type);
      for (uint64_t e = 0; e < b.count; ++e, ++fileCell, pos += nv) {
        int64_t v[8];
        for (uint32_t k = 0; k < nv; ++k) {
          int64_t node = nodeAt(pos + b.perm[k]);
          if (node < 1 || uint64_t(node) > n.nodes)
            throw FileError(src_, mesh::cellTypeName(b.type), " ", e, " (cell ", fileCell,
                            ") refers to node ", node, " but nodes are numbered 1 to ", n.nodes);
          v[k] = node - 1;
        }
        builder_.addCell(b.type, {v, nv}, fileCell);
      }
    }
  }

  // Side files <stem>.<FIELD>.f32 or <stem>.<FIELD>.<STEP>.f32 beside the grid.
  void readSideFields() {
    if (!options_.loadFields) return;
    std::string dir = directoryOf(src_);
    std::vector<std::pair<ArrayInfo, std::string>> found;
    const std::string prefix = stem_ + ".";
    // Another grid whose stem extends this one ("wing.fine" beside "wing") owns the side files
    // named after it: "wing.fine.mach.f32" is not this grid's field "fine.mach".
    std::vector<std::string> otherPrefixes;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir.empty() ? "." : dir, ec)) {
      const std::string name = entry.path().filename().string();
      if (name.size() > 6 && name.compare(name.size() - 6, 6, ".ugrid") == 0) {
        const std::string other = variantOf(name).second;
        if (other != stem_ && other.rfind(prefix, 0) == 0) otherPrefixes.push_back(other + ".");
      }
    }
    for (const auto& entry : fs::directory_iterator(dir.empty() ? "." : dir, ec)) {
      std::string name = entry.path().filename().string();
      if (name.size() <= prefix.size() + 4 || name.rfind(prefix, 0) != 0 ||
          name.compare(name.size() - 4, 4, ".f32") != 0)
        continue;
      if (std::any_of(otherPrefixes.begin(), otherPrefixes.end(),
                      [&](const std::string& p) { return name.rfind(p, 0) == 0; }))
        continue;
      std::string middle = name.substr(prefix.size(), name.size() - prefix.size() - 4);
      size_t dot = middle.rfind('.');
      if (dot != std::string::npos && dot + 1 < middle.size() &&
          std::all_of(middle.begin() + dot + 1, middle.end(),
                      [](unsigned char c) { return std::isdigit(c); })) {
        // Solvers often zero-pad step numbers in file names (wing.p.0001.f32): step 1.
        const size_t digits = middle.find_first_not_of('0', dot + 1);
        middle = middle.substr(0, dot) + "@t" +
                 (digits == std::string::npos ? std::string("0") : middle.substr(digits));
      }
      found.push_back({{middle, 1, false}, joinPath(dir, name)});
    }
    std::sort(found.begin(), found.end(),
              [](const auto& a, const auto& b) { return a.second < b.second; });
    std::vector<ArrayInfo> infos;
    for (const auto& f : found) infos.push_back(f.first);
    for (const FieldLoad& load : planFields(src_, infos, options_))
      builder_.addFieldStep(load.field, load.step, readSideFile(found[load.array].second));
  }

  std::vector<float> readSideFile(const std::string& path) const {
    FileBytes f = FileBytes::open(path);
    if (f.size() != counts_.nodes * 4)
      throw FileError(path, "has ", f.size(), " bytes; a field of ", src_, " needs ", counts_.nodes,
                      " x 4 = ", counts_.nodes * 4, " (one little-endian float32 per node)");
    return toFloats(
        NumericArray::view(ScalarType::Float32, 1, counts_.nodes, f.data(), needsSwap(false)), -1,
        options_.threads);
  }

  FileBytes& bytes_;
  const std::string& src_;
  const ReadOptions& options_;
  bool sideFiles_;
  Variant variant_ = kAscii;
  std::string stem_;
  bool swap_ = false;
  Counts counts_{};
  mesh::MeshBuilder builder_;
};

}  // namespace

mesh::UnstructuredMesh readUgrid(FileBytes bytes, const std::string& source,
                                 const ReadOptions& options, bool sideFiles) {
  return UgridReader(bytes, source, options, sideFiles).read();
}

}  // namespace sm::io
