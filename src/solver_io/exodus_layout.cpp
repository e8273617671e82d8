// Exodus II headers (docs/FORMATS.md): element blocks, variables, time steps, and the files of a
// decomposed mesh. Nothing bulky is read here: exodusLayout is what ranks call to share pieces.
#include <dlfcn.h>
#include <exodusII.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <optional>
#include <regex>

#include "common/error.h"
#include "common/file_util.h"
#include "io_core/file_bytes.h"
#include "solver_io/exodus_file.h"
#include "solver_io/pieced_readers.h"

namespace sm::io {
namespace {

std::string upper(std::string s) {
  for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

// Fortran writers pad names with blanks; a damaged name may lack its terminating zero.
std::string trimmed(const char* text, size_t capacity) {
  std::string s(text, strnlen(text, capacity));
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  return s;
}

bool startsWith(const std::string& s, std::initializer_list<const char*> prefixes) {
  for (const char* p : prefixes)
    if (s.rfind(p, 0) == 0) return true;
  return false;
}

// Exodus element type names are matched by prefix, case-insensitively, as SEACAS does ("HEX",
// "hex8", "HEX27", "TETRA10", "tet"). Higher-order elements list their corners first.
void classify(ExodusBlock& b) {
  const std::string t = upper(b.type);
  struct Shape {
    const char* prefix;
    int corners, lagrangeVtkType;
  };
  static const Shape volumes[] = {
      {"HEX", 8, 72}, {"TET", 4, 71}, {"WEDGE", 6, 73}, {"PYRA", 5, 74}};
  for (const Shape& s : volumes)
    if (t.rfind(s.prefix, 0) == 0) {
      b.volume = true;
      b.corners = s.corners;
      b.vtkType = s.lagrangeVtkType;
      return;
    }
  if (startsWith(t, {"SHELL", "QUAD", "TRI", "NSIDED"}))
    b.vtkType = 7;  // polygon: a 2D cell
  else if (startsWith(t, {"BAR", "TRUSS", "BEAM", "EDGE", "ROD", "SPRING"}))
    b.vtkType = 3;  // line
  else if (startsWith(t, {"SPHERE", "CIRCLE", "POINT"}))
    b.vtkType = 1;  // vertex
  else if (startsWith(t, {"NFACED"}))
    b.vtkType = 42;  // polyhedron, given by faces this reader does not read
}

std::string lastLibraryError() {
  const char *msg = nullptr, *func = nullptr;
  int code = 0;
  ex_get_err(&msg, &func, &code);
  if (msg && *msg) return concat(trimmed(msg, 512), " (code ", code, ")");
  return concat("error code ", code);
}

bool isHdf5(const std::string& path) {
  const std::string head = FileBytes::readPrefix(path, 8);
  return head.size() == 8 && head.compare(0, 8, "\x89HDF\r\n\x1a\n") == 0;
}

// libexodusii 6.02 prints to stderr, whatever ex_opts says, when netCDF fails to open an HDF5
// file (it takes the failure for a netCDF built without netCDF-4). Opening such a file with
// netCDF first, through the library libexodusii has loaded, finds those failures quietly. (The
// symbols are looked up because the build links libexodusii only.)
void checkNetcdf4Opens(const std::string& path) {
  using Open = int (*)(const char*, int, int*);
  using Close = int (*)(int);
  using Describe = const char* (*)(int);
  static const auto open = reinterpret_cast<Open>(dlsym(RTLD_DEFAULT, "nc_open"));
  static const auto close = reinterpret_cast<Close>(dlsym(RTLD_DEFAULT, "nc_close"));
  static const auto describe = reinterpret_cast<Describe>(dlsym(RTLD_DEFAULT, "nc_strerror"));
  if (!open || !close || !describe) return;
  int id = -1;
  const int rc = open(path.c_str(), 0 /* NC_NOWRITE */, &id);
  if (rc == 0) {
    close(id);
    return;
  }
  throw FileError(path, "is a netCDF-4 (HDF5) file that netCDF cannot open (", describe(rc),
                  "): truncated or damaged?");
}

std::string zeroPadded(uint64_t k, size_t width) {
  std::string s = std::to_string(k);
  return std::string(width > s.size() ? width - s.size() : 0, '0') + s;
}

bool isExodusExtension(const std::string& ext) {
  return ext == ".e" || ext == ".exo" || ext == ".ex2" || ext == ".exii" || ext == ".g" ||
         ext == ".gen";
}

// NAME.e.N.i: NAME.e.N.0 .. NAME.e.N.(N-1), the rank padded to the width of the name given (SEACAS
// pads to the digits of N: mesh.e.16.07), an unpadded name accepted too.
std::vector<std::string> setFiles(const std::string& path, const std::string& base,
                                  const std::string& count, const std::string& rank) {
  uint64_t n = 0, i = 0;
  if (count.size() > 7 || rank.size() > 7 || (n = std::stoull(count)) == 0)
    throw FileError(path, "names a decomposed mesh of ", count, " files, which cannot be");
  if ((i = std::stoull(rank)) >= n)
    throw FileError(path, "names file ", i, " of a decomposed mesh of ", n, " files (0 to ", n - 1,
                    ")");
  std::vector<std::string> files;
  for (uint64_t k = 0; k < n; ++k) {
    const std::string padded = concat(base, ".", n, ".", zeroPadded(k, rank.size()));
    const std::string plain = concat(base, ".", n, ".", k);
    if (fileExists(padded))
      files.push_back(padded);
    else if (fileExists(plain))
      files.push_back(plain);
    else
      throw FileError(padded, "is missing: the decomposed Exodus mesh ", base, " has ", n,
                      " files (", base, ".", n, ".", zeroPadded(0, rank.size()), " to ", base, ".",
                      n, ".", zeroPadded(n - 1, rank.size()), ")");
  }
  return files;
}

// NAME.e absent: the first file of the one decomposed set beside it (NAME.e.N.0...).
std::optional<std::string> firstSetFile(const std::string& path) {
  namespace fs = std::filesystem;
  const std::string dir = directoryOf(path), name = fs::path(path).filename().string();
  const std::regex first(R"(\.[0-9]+\.0+)");
  std::vector<std::string> found;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir.empty() ? "." : dir, ec)) {
    const std::string f = entry.path().filename().string();
    if (f.size() > name.size() && f.compare(0, name.size(), name) == 0 &&
        std::regex_match(f.substr(name.size()), first))
      found.push_back(joinPath(dir, f));
  }
  if (found.empty()) return std::nullopt;
  std::sort(found.begin(), found.end());
  if (found.size() > 1)
    throw FileError(path, "does not exist, and ", found.size(),
                    " decomposed meshes of that name do (", found[0], ", ", found[1],
                    "...): name a file of the one to read");
  return found[0];
}

void checkSameVariables(const ExodusHeader& a, const std::string& fileA, const ExodusHeader& b,
                        const std::string& fileB) {
  auto list = [](const std::vector<std::string>& names) {
    std::string s;
    for (const std::string& n : names) s += concat(s.empty() ? "'" : ", '", n, "'");
    return s.empty() ? std::string("none") : s;
  };
  if (a.nodalVars != b.nodalVars)
    throw FileError(fileB, "has nodal variables ", list(b.nodalVars), " but ", fileA,
                    " of the same decomposed mesh has ", list(a.nodalVars));
  if (a.elemVars != b.elemVars)
    throw FileError(fileB, "has element variables ", list(b.elemVars), " but ", fileA,
                    " of the same decomposed mesh has ", list(a.elemVars));
  if (a.times.size() != b.times.size())
    throw FileError(fileB, "has ", b.times.size(), " time steps but ", fileA,
                    " of the same decomposed mesh has ", a.times.size());
}

}  // namespace

std::string ExodusBlock::place() const {
  return name.empty() ? concat("block ", id) : concat("block ", id, " '", name, "'");
}

uint64_t ExodusHeader::volumeCells() const {
  uint64_t n = 0;
  for (const ExodusBlock& b : blocks)
    if (b.volume) n += uint64_t(b.elements);
  return n;
}

ExodusFile::ExodusFile(std::string path) : path_(std::move(path)) {
  if (!fileExists(path_)) throw FileError(path_, "does not exist");
  fileSize_ = fileSize(path_);
  // A netCDF-4 (HDF5) file may be compressed: an array can hold far more values than bytes.
  const std::optional<uint64_t> extent = netcdfClassicExtent(path_);
  header_.maxValues = extent ? fileSize_ / 4 : fileSize_ * 258;
  if (extent && *extent > fileSize_)
    throw FileError(path_, "is truncated: its netCDF header places data up to byte ", *extent,
                    " but the file has ", fileSize_, " bytes");
  if (!extent && isHdf5(path_)) checkNetcdf4Opens(path_);
  ex_opts(0);  // errors come back as codes: no printing, no exit()
  int cpuWordSize = 8, ioWordSize = 0;
  float version = 0;
  id_ = ex_open(path_.c_str(), EX_READ, &cpuWordSize, &ioWordSize, &version);
  if (id_ < 0)
    throw FileError(path_, "is not an Exodus II file that libexodusii can open (",
                    lastLibraryError(), ")");
  try {
    ex_set_int64_status(id_, EX_ALL_INT64_API);
    readHeader();
  } catch (...) {
    ex_close(id_);
    throw;
  }
}

ExodusFile::~ExodusFile() {
  if (id_ >= 0) ex_close(id_);
}

void ExodusFile::check(int rc, const std::string& what) const {
  if (rc < 0) throw FileError(path_, what, ": ", lastLibraryError());
}

void ExodusFile::checkCount(uint64_t count, const std::string& what) const {
  if (count > header_.maxValues)
    throw FileError(path_, what, ": ", count, " values declared, impossible for a file of ",
                    fileSize_, " bytes");
}

void ExodusFile::readHeader() {
  ex_init_params p{};
  check(ex_get_init_ext(id_, &p), "the header (ex_get_init)");
  if (p.num_dim != 3)
    throw FileError(path_, "is a ", p.num_dim, "D mesh (num_dim ", p.num_dim,
                    "): shellmarch renders 3D volume meshes only");
  if (p.num_nodes < 0 || p.num_elem < 0 || p.num_elem_blk < 0)
    throw FileError(path_, "the header declares negative counts");
  checkCount(3 * uint64_t(p.num_nodes), "node coordinates");
  checkCount(uint64_t(p.num_elem), "elements");
  checkCount(uint64_t(p.num_elem_blk) * 8, "element blocks");
  header_.nodes = p.num_nodes;
  header_.elements = p.num_elem;
  header_.blocks.resize(size_t(p.num_elem_blk));
  readBlocks();
  readVariables();
}

void ExodusFile::readBlocks() {
  std::vector<ExodusBlock>& blocks = header_.blocks;
  if (blocks.empty()) return;
  std::vector<int64_t> ids(blocks.size());
  check(ex_get_elem_blk_ids(id_, ids.data()), "element block ids");
  const int64_t used = ex_inquire_int(id_, EX_INQ_DB_MAX_USED_NAME_LENGTH);
  const size_t nameLength = size_t(std::clamp<int64_t>(used, MAX_STR_LENGTH, 255));
  ex_set_max_name_length(id_, int(nameLength));
  std::vector<std::vector<char>> names(blocks.size(), std::vector<char>(nameLength + 1, 0));
  std::vector<char*> pointers;
  for (auto& n : names) pointers.push_back(n.data());
  check(ex_get_names(id_, EX_ELEM_BLOCK, pointers.data()), "element block names");
  int64_t total = 0;
  for (size_t i = 0; i < blocks.size(); ++i) {
    ExodusBlock& b = blocks[i];
    b.id = ids[i];
    b.name = trimmed(names[i].data(), nameLength);
    char type[MAX_STR_LENGTH + 1] = {};
    int64_t attributes = 0;
    check(ex_get_elem_block(id_, b.id, type, &b.elements, &b.nodesPerElement, &attributes),
          b.place());
    b.type = trimmed(type, MAX_STR_LENGTH);
    if (b.elements < 0 || b.nodesPerElement < 0 || b.elements > header_.elements - total)
      throw FileError(path_, b.place(), ": ", b.elements, " elements of ", b.nodesPerElement,
                      " nodes, but the file has ", header_.elements, " elements in all");
    total += b.elements;
    if (b.elements == 0) continue;
    classify(b);
    if (!b.volume) continue;
    checkCount(uint64_t(b.elements) * uint64_t(b.nodesPerElement), b.place() + " connectivity");
    if (b.nodesPerElement > 64)  // the most any Exodus volume element has is 27
      throw FileError(path_, b.place(), ": element type '", b.type, "' with ", b.nodesPerElement,
                      " nodes per element");
    if (b.nodesPerElement < b.corners)
      throw FileError(path_, b.place(), ": element type '", b.type, "' with ", b.nodesPerElement,
                      " nodes per element (it has ", b.corners, " corners)");
  }
  if (total != header_.elements)
    throw FileError(path_, "its element blocks hold ", total, " elements but the header says ",
                    header_.elements);
}

void ExodusFile::readVariables() {
  auto names = [&](const char* kind, const char* what) {
    int n = 0;
    check(ex_get_var_param(id_, kind, &n), concat(what, " variables"));
    checkCount(uint64_t(std::max(n, 0)) * MAX_STR_LENGTH, concat(what, " variable names"));
    std::vector<std::vector<char>> buffers(size_t(std::max(n, 0)), std::vector<char>(256, 0));
    std::vector<char*> pointers;
    for (auto& b : buffers) pointers.push_back(b.data());
    if (n > 0)
      check(ex_get_var_names(id_, kind, n, pointers.data()), concat(what, " variable names"));
    std::vector<std::string> out;
    for (auto& b : buffers) {
      out.push_back(trimmed(b.data(), 255));
      if (out.back().empty()) out.back() = concat(what, "_", out.size());
    }
    return out;
  };
  header_.nodalVars = names("n", "nodal");
  header_.elemVars = names("e", "element");
  const size_t nb = header_.blocks.size(), nv = header_.elemVars.size();
  if (nb > 0 && nv > 0) {
    checkCount(uint64_t(nb) * nv, "the element variable truth table");
    header_.truth.assign(nb * nv, 0);
    check(ex_get_elem_var_tab(id_, int(nb), int(nv), header_.truth.data()),
          "the element variable truth table");
  }
  const int64_t steps = ex_inquire_int(id_, EX_INQ_TIME);
  if (steps < 0) check(int(steps), "the time steps");
  checkCount(uint64_t(steps), "time steps");
  header_.times.resize(size_t(steps));
  if (steps > 0) check(ex_get_all_times(id_, header_.times.data()), "the time values");
}

std::vector<std::string> exodusFiles(const std::string& path) {
  static const std::regex decomposed(R"((.*)\.([0-9]+)\.([0-9]+))");
  std::smatch m;
  if (std::regex_match(path, m, decomposed) && isExodusExtension(fileExtension(m[1].str())))
    return setFiles(path, m[1].str(), m[2].str(), m[3].str());
  if (fileExists(path)) return {path};
  if (std::optional<std::string> first = firstSetFile(path)) return exodusFiles(*first);
  throw FileError(path, "does not exist (nor a decomposed mesh ", path, ".N.0 ...)");
}

PiecedLayout exodusLayout(const std::string& path) {
  PiecedLayout layout;
  layout.files = exodusFiles(path);
  const bool decomposed = exodusPiecesAreFiles(path, layout.files);
  ExodusHeader first;
  for (size_t i = 0; i < layout.files.size(); ++i) {
    const std::string& f = layout.files[i];
    ExodusFile file(f);
    const ExodusHeader& h = file.header();
    if (decomposed) {
      layout.pieces.push_back(f);
      layout.pieceCells.push_back(h.volumeCells());
    } else {
      for (const ExodusBlock& b : h.blocks) {
        layout.pieces.push_back(concat(f, ", ", b.place()));
        layout.pieceCells.push_back(b.volume ? uint64_t(b.elements) : 0);
      }
    }
    if (i == 0)
      first = h;
    else
      checkSameVariables(first, layout.files[0], h, f);
  }
  if (layout.pieces.empty()) throw FileError(path, "has no element blocks");
  layout.times = first.times;
  // Variables are stored per time step: a file without steps has no values to show.
  if (!first.times.empty()) {
    for (const std::string& n : first.nodalVars)
      layout.fields.push_back({n, first.times.size(), false, 1});
    for (const std::string& n : first.elemVars)
      layout.fields.push_back({n, first.times.size(), true, 1});
  }
  return layout;
}

}  // namespace sm::io
