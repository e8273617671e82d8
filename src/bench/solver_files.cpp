#include "bench/solver_files.h"

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include <cgnslib.h>
#include <exodusII.h>

#include "common/error.h"

namespace sm::app::bench {
namespace {

using mesh::CellType;

constexpr std::array<ElementType_t, 4> kCgnsTypes = {CGNS_ENUMV(TETRA_4), CGNS_ENUMV(PYRA_5),
                                                     CGNS_ENUMV(PENTA_6), CGNS_ENUMV(HEXA_8)};
constexpr std::array<const char*, 4> kExodusTypes = {"TETRA", "PYRAMID", "WEDGE", "HEX"};

// Vertex k of an element as CGNS and Exodus number it is VTK's vertex order[k]: the same but for
// wedges, whose first triangle those formats wind towards the second and VTK away from it.
const std::array<uint32_t, 8>& solverOrder(CellType t) {
  static constexpr std::array<uint32_t, 8> kIdentity = {0, 1, 2, 3, 4, 5, 6, 7};
  static constexpr std::array<uint32_t, 8> kWedge = {0, 2, 1, 3, 5, 4, 6, 7};
  return t == CellType::Wedge ? kWedge : kIdentity;
}

void cgCheck(int status, const std::string& path, const char* what) {
  if (status != CG_OK) throw FileError(path, "libcgns: ", what, ": ", cg_get_error());
}

// One cluster's elements with its own points, numbered from 1 as CGNS numbers them.
struct ZoneCopy {
  std::vector<uint32_t> points;  // mesh point of each zone point
  std::array<std::vector<cgsize_t>, 4> cells;
};

std::vector<ZoneCopy> zonesOf(const mesh::UnstructuredMesh& m) {
  std::vector<ZoneCopy> zones(size_t(std::max(m.numClusters(), 1)));
  std::vector<int64_t> local(m.numPoints(), -1);
  std::vector<int32_t> owner(m.numPoints(), -1);
  for (CellType t : mesh::kAllCellTypes) {
    const uint32_t ti = mesh::typeIndex(t), nv = mesh::numVerts(t);
    for (size_t e = 0; e < m.clusters[ti].size(); ++e) {
      const int32_t c = m.clusters[ti][e];
      ZoneCopy& z = zones[size_t(c)];
      for (uint32_t k = 0; k < nv; ++k) {
        const uint32_t p = m.cells[ti][e * nv + solverOrder(t)[k]];
        if (owner[p] != c) {
          owner[p] = c;
          local[p] = int64_t(z.points.size());
          z.points.push_back(p);
        }
        z.cells[ti].push_back(cgsize_t(local[p] + 1));
      }
    }
  }
  return zones;
}

void writeZone(int fn, int base, int index, const ZoneCopy& z, const mesh::UnstructuredMesh& m,
               const std::string& path) {
  uint64_t cells = 0;
  for (CellType t : mesh::kAllCellTypes)
    cells += z.cells[mesh::typeIndex(t)].size() / mesh::numVerts(t);
  cgsize_t size[3] = {cgsize_t(z.points.size()), cgsize_t(cells), 0};
  int zone = 0;
  cgCheck(
      cg_zone_write(fn, base, concat("zone", index).c_str(), size, CGNS_ENUMV(Unstructured), &zone),
      path, "zone");
  std::vector<double> coord(z.points.size());
  const char* names[3] = {"CoordinateX", "CoordinateY", "CoordinateZ"};
  for (int a = 0; a < 3; ++a) {
    for (size_t i = 0; i < z.points.size(); ++i) coord[i] = m.points[z.points[i]][a];
    int c = 0;
    cgCheck(cg_coord_write(fn, base, zone, CGNS_ENUMV(RealDouble), names[a], coord.data(), &c),
            path, "coordinates");
  }
  cgsize_t first = 1;
  for (CellType t : mesh::kAllCellTypes) {
    const uint32_t ti = mesh::typeIndex(t);
    const cgsize_t n = cgsize_t(z.cells[ti].size() / mesh::numVerts(t));
    if (n == 0) continue;
    int s = 0;
    cgCheck(cg_section_write(fn, base, zone, std::string(mesh::cellTypePluralName(t)).c_str(),
                             kCgnsTypes[ti], first, first + n - 1, 0, z.cells[ti].data(), &s),
            path, "section");
    first += n;
  }
  if (m.fields.empty()) return;
  int sol = 0;
  cgCheck(cg_sol_write(fn, base, zone, "FlowSolution", CGNS_ENUMV(Vertex), &sol), path, "solution");
  std::vector<float> values(z.points.size());
  for (const mesh::Field& f : m.fields) {
    for (size_t i = 0; i < z.points.size(); ++i) values[i] = f.steps.at(0)[z.points[i]];
    int field = 0;
    cgCheck(cg_field_write(fn, base, zone, sol, CGNS_ENUMV(RealSingle), f.name.c_str(),
                           values.data(), &field),
            path, "field");
  }
}

void exCheck(int status, const std::string& path, const char* what) {
  if (status < 0) throw FileError(path, "libexodusii: ", what, " failed (", status, ")");
}

}  // namespace

void writeCgnsCopy(const std::string& path, const mesh::UnstructuredMesh& m) {
  const std::string tmp = path + ".tmp";
  int fn = 0;
  cgCheck(cg_open(tmp.c_str(), CG_MODE_WRITE, &fn), path, "open");
  try {
    int base = 0;
    cgCheck(cg_base_write(fn, "Base", 3, 3, &base), path, "base");
    const std::vector<ZoneCopy> zones = zonesOf(m);
    for (size_t i = 0; i < zones.size(); ++i) writeZone(fn, base, int(i), zones[i], m, path);
  } catch (...) {
    cg_close(fn);
    throw;
  }
  cgCheck(cg_close(fn), path, "close");
  std::filesystem::rename(tmp, path);
}

void writeExodusCopy(const std::string& path, const mesh::UnstructuredMesh& m) {
  const std::string tmp = path + ".tmp";
  int cpu = 8, io = 8;
  ex_opts(0);  // errors come back as codes; the library neither prints nor exits
  const int ex = ex_create(tmp.c_str(), EX_CLOBBER | EX_LARGE_MODEL, &cpu, &io);
  if (ex < 0) throw FileError(path, "libexodusii: cannot create the file");
  try {
    // One block per cluster and type: blocks hold one element type each.
    struct Block {
      int32_t cluster;
      CellType type;
      std::vector<int> conn;
    };
    std::vector<Block> blocks;
    for (int32_t c = 0; c < std::max(m.numClusters(), 1); ++c)
      for (CellType t : mesh::kAllCellTypes) blocks.push_back({c, t, {}});
    for (CellType t : mesh::kAllCellTypes) {
      const uint32_t ti = mesh::typeIndex(t), nv = mesh::numVerts(t);
      for (size_t e = 0; e < m.clusters[ti].size(); ++e) {
        std::vector<int>& conn = blocks[size_t(m.clusters[ti][e]) * 4 + ti].conn;
        const auto& order = solverOrder(t);
        for (uint32_t k = 0; k < nv; ++k) conn.push_back(int(m.cells[ti][e * nv + order[k]]) + 1);
      }
    }
    std::erase_if(blocks, [](const Block& b) { return b.conn.empty(); });
    exCheck(ex_put_init(ex, "shellmarch bench", 3, int64_t(m.numPoints()), int64_t(m.numCells()),
                        int64_t(blocks.size()), 0, 0),
            path, "init");
    std::array<std::vector<double>, 3> xyz;
    for (int a = 0; a < 3; ++a)
      for (const glm::dvec3& p : m.points) xyz[a].push_back(p[a]);
    exCheck(ex_put_coord(ex, xyz[0].data(), xyz[1].data(), xyz[2].data()), path, "coordinates");
    for (size_t b = 0; b < blocks.size(); ++b) {
      const uint32_t nv = mesh::numVerts(blocks[b].type);
      exCheck(ex_put_elem_block(ex, int64_t(b + 1), kExodusTypes[mesh::typeIndex(blocks[b].type)],
                                int64_t(blocks[b].conn.size() / nv), nv, 0),
              path, "block");
      exCheck(ex_put_elem_conn(ex, int64_t(b + 1), blocks[b].conn.data()), path, "connectivity");
    }
    if (!m.fields.empty()) {
      exCheck(ex_put_var_param(ex, "n", int(m.fields.size())), path, "variables");
      std::vector<char*> names;
      for (const mesh::Field& f : m.fields) names.push_back(const_cast<char*>(f.name.c_str()));
      exCheck(ex_put_var_names(ex, "n", int(names.size()), names.data()), path, "names");
      const double time = 0;
      exCheck(ex_put_time(ex, 1, &time), path, "time");
      for (size_t k = 0; k < m.fields.size(); ++k) {
        // The file stores doubles (io_ws 8).
        std::vector<double> v(m.fields[k].steps.at(0).begin(), m.fields[k].steps.at(0).end());
        exCheck(ex_put_nodal_var(ex, 1, int(k + 1), int64_t(v.size()), v.data()), path, "field");
      }
    }
  } catch (...) {
    ex_close(ex);
    throw;
  }
  exCheck(ex_close(ex), path, "close");
  std::filesystem::rename(tmp, path);
}

}  // namespace sm::app::bench
