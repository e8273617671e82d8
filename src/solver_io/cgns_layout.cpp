// CGNS headers: bases, zones, solutions and time steps (docs/FORMATS.md, CGNS).
#include "solver_io/cgns_layout.h"

#include <cgns_io.h>
#include <cgnslib.h>
#include <dlfcn.h>

#include <algorithm>
#include <cstring>
#include <filesystem>

#include "common/log.h"

namespace sm::io::cgns {
namespace {

std::mutex& libraryLock() {
  static std::mutex m;
  return m;
}

void ignoreMessage(int, char*) {}

// libcgns prints its warnings, and HDF5 its whole error stack, for each failed call on a damaged
// file; the reader reports one line instead. HDF5's setting is per thread in thread-safe builds, so
// this runs at every open. HDF5 is libcgns's dependency, not ours: found at run time, not linked.
void quietLibraries() {
  cg_configure(CG_CONFIG_ERROR, reinterpret_cast<void*>(&ignoreMessage));
  using SetAuto = int (*)(int64_t, void*, void*);
  static const auto setAuto = reinterpret_cast<SetAuto>(dlsym(RTLD_DEFAULT, "H5Eset_auto2"));
  if (setAuto) setAuto(0 /* H5E_DEFAULT */, nullptr, nullptr);
}

std::string trimmed(const char* text, size_t n) {
  std::string s(text, strnlen(text, n));
  while (!s.empty() && (s.back() == ' ' || s.back() == '\0')) s.pop_back();
  return s;
}

// The DataArray `name` under the node cg_goto last reached: its index, element count and dims;
// index 0 when it is not there.
struct ArrayInfo {
  int index = 0;
  DataType_t type = DataTypeNull;
  int dims = 0;
  cgsize_t dim[12]{};
  uint64_t count = 0;
};

ArrayInfo findArray(const char* name) {
  int n = 0;
  if (cg_narrays(&n) != CG_OK) return {};
  for (int a = 1; a <= n; ++a) {
    ArrayInfo info;
    char found[33] = {};
    if (cg_array_info(a, found, &info.type, &info.dims, info.dim) != CG_OK) continue;
    if (std::string(found) != name) continue;
    info.index = a;
    info.count = info.dims > 0 ? 1 : 0;
    for (int d = 0; d < info.dims && d < 12; ++d)
      info.count *= info.dim[d] < 0 ? 0 : uint64_t(info.dim[d]);
    return info;
  }
  return {};
}

// FlowSolutionPointers of a zone's ZoneIterativeData: the solution of each step, by name.
std::vector<std::string> solutionPointers(const File& f, const Zone& z) {
  char name[33] = {};
  if (cg_ziter_read(f.fn(), z.base, z.zone, name) != CG_OK) return {};
  if (cg_goto(f.fn(), z.base, "Zone_t", z.zone, "ZoneIterativeData_t", 1, "end") != CG_OK)
    return {};
  const ArrayInfo a = findArray("FlowSolutionPointers");
  if (!a.index || a.type != Character || a.dims != 2 || a.dim[0] <= 0) return {};
  f.checkFits(a.count, 1, z.where(), "FlowSolutionPointers");
  std::vector<char> text(a.count);
  f.check(cg_array_read(a.index, text.data()), z.where(), "reading FlowSolutionPointers");
  std::vector<std::string> names;
  for (cgsize_t s = 0; s < a.dim[1]; ++s)
    names.push_back(trimmed(text.data() + s * a.dim[0], size_t(a.dim[0])));
  return names;
}

std::vector<double> timeValues(const File& f, int base) {
  char name[33] = {};
  int steps = 0;
  if (cg_biter_read(f.fn(), base, name, &steps) != CG_OK) return {};
  if (cg_goto(f.fn(), base, "BaseIterativeData_t", 1, "end") != CG_OK) return {};
  const ArrayInfo a = findArray("TimeValues");
  if (!a.index || a.dims != 1) return {};
  f.checkFits(a.count, 4, concat("base ", base), "TimeValues");
  std::vector<double> t(a.count);
  f.check(cg_array_read_as(a.index, RealDouble, t.data()), concat("base ", base),
          "reading TimeValues");
  return t;
}

void readSolutions(const File& f, Zone& z) {
  int n = 0;
  f.check(cg_nsols(f.fn(), z.base, z.zone, &n), z.where(), "counting solutions");
  std::vector<std::pair<Solution, GridLocation_t>> all;
  for (int s = 1; s <= n; ++s) {
    char name[33] = {};
    GridLocation_t where{};
    f.check(cg_sol_info(f.fn(), z.base, z.zone, s, name, &where), z.where(), "solution info");
    PointSetType_t ptset{};
    cgsize_t points = 0;
    if (cg_sol_ptset_info(f.fn(), z.base, z.zone, s, &ptset, &points) == CG_OK &&
        ptset != PointSetTypeNull) {
      log::info(f.path(), ": ", z.where(), " solution '", name,
                "' covers a point set, not the whole zone: skipped");
      continue;
    }
    if (where != Vertex && where != CellCenter) {
      log::info(f.path(), ": ", z.where(), " solution '", name, "' is at ",
                cg_GridLocationName(where), ", not Vertex or CellCenter: skipped");
      continue;
    }
    Solution sol{s, name, {}};
    int fields = 0;
    f.check(cg_nfields(f.fn(), z.base, z.zone, s, &fields), z.where(), "counting fields");
    for (int k = 1; k <= fields; ++k) {
      char field[33] = {};
      DataType_t type{};
      f.check(cg_field_info(f.fn(), z.base, z.zone, s, k, &type, field), z.where(), "field info");
      sol.fields.push_back(field);
    }
    all.push_back({std::move(sol), where});
  }
  // Steps in the order FlowSolutionPointers gives, then solutions it does not name.
  std::vector<std::pair<Solution, GridLocation_t>> ordered;
  for (const std::string& p : solutionPointers(f, z))
    for (auto& s : all)
      if (s.second != GridLocationNull && s.first.name == p) {
        ordered.push_back(s);
        s.second = GridLocationNull;
      }
  for (auto& s : all)
    if (s.second != GridLocationNull) ordered.push_back(s);
  for (auto& [sol, where] : ordered)
    (where == Vertex ? z.vertexSolutions : z.cellSolutions).push_back(std::move(sol));
}

Zone readZone(const File& f, int base, const std::string& baseName, int zone) {
  Zone z;
  z.base = base;
  z.zone = zone;
  z.baseName = baseName;
  char name[33] = {};
  cgsize_t size[9] = {};
  f.check(cg_zone_read(f.fn(), base, zone, name, size), concat("base '", baseName, "' zone ", zone),
          "reading the zone");
  z.name = name;
  ZoneType_t type{};
  f.check(cg_zone_type(f.fn(), base, zone, &type), z.where(), "zone type");
  z.structured = type == Structured;
  if (z.structured) {
    z.vertices = z.cells = 1;
    for (int d = 0; d < 3; ++d) {
      if (size[d] < 1) throw FileError(f.path(), z.where(), ": ", size[d], " vertices along ", d);
      z.dims[d] = size[d];
      z.vertices *= uint64_t(size[d]);
      z.cells *= uint64_t(size[d] - 1);
    }
  } else if (type == Unstructured) {
    if (size[0] < 0 || size[1] < 0)
      throw FileError(f.path(), z.where(), ": declares ", size[0], " vertices and ", size[1],
                      " cells");
    z.vertices = uint64_t(size[0]);
    z.cells = uint64_t(size[1]);
  } else {
    throw FileError(f.path(), z.where(), ": zone type ", cg_ZoneTypeName(type));
  }
  // Each vertex needs 3 coordinates of 4 bytes at least, each cell 4 ids of 4 bytes (structured
  // cells none).
  f.checkFits(z.vertices, 12, z.where(), concat(z.vertices, " vertices"));
  if (!z.structured) f.checkFits(z.cells, 16, z.where(), concat(z.cells, " cells"));
  readSolutions(f, z);
  return z;
}

// Each DataArray of each location a field: its steps are the solutions that hold it.
void addFields(std::vector<FieldStepCount>& fields, const std::vector<Solution>& solutions,
               bool cellData) {
  std::vector<FieldStepCount> own;
  for (const Solution& s : solutions)
    for (const std::string& name : s.fields) {
      auto it = std::find_if(own.begin(), own.end(),
                             [&](const FieldStepCount& c) { return c.name == name; });
      if (it == own.end())
        own.push_back({name, 1, cellData, 1});
      else
        ++it->steps;
    }
  for (const FieldStepCount& c : own) {
    auto it = std::find_if(fields.begin(), fields.end(), [&](const FieldStepCount& d) {
      return d.name == c.name && d.cellData == c.cellData;
    });
    if (it == fields.end())
      fields.push_back(c);
    else
      it->steps = std::max(it->steps, c.steps);
  }
}

}  // namespace

File::File(const std::string& path) : lock_(libraryLock()), path_(path) {
  std::error_code ec;
  bytes_ = std::filesystem::file_size(path, ec);
  if (ec) throw FileError(path, "cannot be read: ", ec.message());
  quietLibraries();
  fn_ = -1;
  if (cg_open(path.c_str(), CG_MODE_READ, &fn_) != CG_OK) {
    const std::string why = cg_get_error();
    // A file whose tree fails to read stays open, its cgio slot taken (after some hundred such
    // files nothing opens). cg_close would free its half-read tree and crash: only the database
    // is closed, the library's record of the file is left (a few bytes).
    int cgio = 0;
    if (fn_ >= 0 && cg_get_cgio(fn_, &cgio) == CG_OK) cgio_close_file(cgio);
    fn_ = -1;
    throw FileError(path, "is not a readable CGNS file (", why, ")");
  }
}

File::~File() {
  if (fn_ >= 0) cg_close(fn_);
}

void File::check(int rc, const std::string& where, const std::string& what) const {
  if (rc != CG_OK) throw FileError(path_, where, ": ", what, ": ", cg_get_error());
}

void File::checkFits(uint64_t count, uint64_t size, const std::string& where,
                     const std::string& what) const {
  if (count > bytes_ / size)
    throw FileError(path_, where, ": ", what, " need ", count, " values of ", size,
                    " bytes at least, more than the file's ", bytes_, " bytes");
}

std::string Zone::where() const {
  return concat("base '", baseName, "' zone '", name, "'");
}

Scan scan(const File& f) {
  Scan out;
  int bases = 0;
  f.check(cg_nbases(f.fn(), &bases), "file", "counting bases");
  std::vector<double> times;
  for (int b = 1; b <= bases; ++b) {
    char name[33] = {};
    int cellDim = 0, physDim = 0, zones = 0;
    f.check(cg_base_read(f.fn(), b, name, &cellDim, &physDim), concat("base ", b), "reading");
    f.check(cg_nzones(f.fn(), b, &zones), concat("base '", name, "'"), "counting zones");
    for (int z = 1; z <= zones; ++z) {
      if (cellDim != 3) {
        cgsize_t size[9] = {};
        char zoneName[33] = {};
        if (cg_zone_read(f.fn(), b, z, zoneName, size) == CG_OK) out.skippedCells += size[1];
        ++out.skippedZones;
        continue;
      }
      out.zones.push_back(readZone(f, b, name, z));
      const Zone& zone = out.zones.back();
      out.layout.pieces.push_back(concat(f.path(), ", ", zone.where()));
      out.layout.pieceCells.push_back(zone.cells);
      addFields(out.layout.fields, zone.vertexSolutions, false);
      addFields(out.layout.fields, zone.cellSolutions, true);
    }
    if (cellDim == 3 && times.empty()) times = timeValues(f, b);
  }
  if (out.zones.empty())
    throw FileError(f.path(), "has no 3D zones (", out.skippedZones,
                    " zones in bases of cell dimension 1 or 2)");
  uint64_t steps = 0;
  for (const FieldStepCount& c : out.layout.fields) steps = std::max(steps, c.steps);
  if (steps > 0 && times.size() == steps) out.layout.times = times;
  out.layout.files = {f.path()};
  return out;
}

}  // namespace sm::io::cgns

namespace sm::io {

PiecedLayout cgnsLayout(const std::string& path) {
  cgns::File file(path);
  return cgns::scan(file).layout;
}

}  // namespace sm::io
