// Exodus II test files written with libexodusii's own writer, so that the reader is tested on the
// library's layout (netCDF dimensions, variable names, truth tables) and not on our idea of it.
#include <exodusII.h>

#include <array>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "format_files.h"

namespace sm::test {
namespace {

void check(int rc, const std::string& path, const char* call) {
  if (rc < 0) throw std::runtime_error(path + ": " + call + " failed (" + std::to_string(rc) + ")");
}

// Nodes numbered by first use, one per coordinate: cells name corners by position.
class Nodes {
 public:
  int at(double x, double y, double z) {
    auto [it, added] = ids_.try_emplace({x, y, z}, int(x_.size()) + 1);
    if (added) {
      x_.push_back(x);
      y_.push_back(y);
      z_.push_back(z);
    }
    return it->second;
  }
  size_t size() const { return x_.size(); }
  const std::vector<double>& x() const { return x_; }
  const std::vector<double>& y() const { return y_; }
  const std::vector<double>& z() const { return z_; }

 private:
  std::map<std::tuple<double, double, double>, int> ids_;
  std::vector<double> x_, y_, z_;
};

struct Block {
  int id;
  std::string name, type;
  int nodesPerElem;
  std::vector<int> conn;  // 1-based
  int numElem() const { return nodesPerElem ? int(conn.size()) / nodesPerElem : 0; }
};

using Field = std::vector<double>;

// The file: nodal variables as functions of the node and step, element variables as functions
// of the block, element and step (with truth[b][v] false: absent on block b).
struct ExodusModel {
  int numDim = 3;
  Nodes nodes;
  std::vector<Block> blocks;
  std::vector<double> times;
  std::vector<std::string> nodalVars, elemVars;
  std::vector<std::vector<int>> truth;
  double (*nodal)(int var, int step, double x, double y, double z) = nullptr;
  double (*elem)(int var, int step, int blockId, int e, double extra) = nullptr;
  double extra = 0;  // passed to elem (the rank of a decomposed file)
};

std::vector<char*> namePointers(std::vector<std::string>& names) {
  std::vector<char*> p;
  for (std::string& n : names) p.push_back(n.data());
  return p;
}

void putVariables(int exo, const std::string& path, ExodusModel& m) {
  if (!m.nodalVars.empty()) {
    check(ex_put_var_param(exo, "n", int(m.nodalVars.size())), path, "ex_put_var_param");
    auto names = namePointers(m.nodalVars);
    check(ex_put_var_names(exo, "n", int(names.size()), names.data()), path, "ex_put_var_names");
  }
  if (!m.elemVars.empty()) {
    check(ex_put_var_param(exo, "e", int(m.elemVars.size())), path, "ex_put_var_param");
    auto names = namePointers(m.elemVars);
    check(ex_put_var_names(exo, "e", int(names.size()), names.data()), path, "ex_put_var_names");
    std::vector<int> tab;
    for (size_t b = 0; b < m.blocks.size(); ++b)
      for (size_t v = 0; v < m.elemVars.size(); ++v) tab.push_back(m.truth[b][v]);
    check(ex_put_elem_var_tab(exo, int(m.blocks.size()), int(m.elemVars.size()), tab.data()), path,
          "ex_put_elem_var_tab");
  }
  const Nodes& n = m.nodes;
  for (size_t s = 0; s < m.times.size(); ++s) {
    const int step = int(s) + 1;
    check(ex_put_time(exo, step, &m.times[s]), path, "ex_put_time");
    for (size_t v = 0; v < m.nodalVars.size(); ++v) {
      Field f(n.size());
      for (size_t i = 0; i < n.size(); ++i)
        f[i] = m.nodal(int(v), int(s), n.x()[i], n.y()[i], n.z()[i]);
      check(ex_put_nodal_var(exo, step, int(v) + 1, int64_t(n.size()), f.data()), path,
            "ex_put_nodal_var");
    }
    for (size_t b = 0; b < m.blocks.size(); ++b)
      for (size_t v = 0; v < m.elemVars.size(); ++v) {
        const Block& blk = m.blocks[b];
        if (!m.truth[b][v] || blk.numElem() == 0) continue;
        Field f(blk.numElem());
        for (int e = 0; e < blk.numElem(); ++e) f[e] = m.elem(int(v), int(s), blk.id, e, m.extra);
        check(ex_put_elem_var(exo, step, int(v) + 1, blk.id, blk.numElem(), f.data()), path,
              "ex_put_elem_var");
      }
  }
}

std::string write(const std::string& path, ExodusModel& m, int mode = 0) {
  int cpuWs = 8, ioWs = 8;
  std::remove(path.c_str());
  const int exo = ex_create(path.c_str(), EX_CLOBBER | mode, &cpuWs, &ioWs);
  if (exo < 0) throw std::runtime_error(path + ": ex_create failed");
  try {
    int64_t elems = 0;
    for (const Block& b : m.blocks) elems += b.numElem();
    check(ex_put_init(exo, "shellmarch test", m.numDim, int64_t(m.nodes.size()), elems,
                      int64_t(m.blocks.size()), 0, 0),
          path, "ex_put_init");
    check(ex_put_coord(exo, m.nodes.x().data(), m.nodes.y().data(),
                       m.numDim == 3 ? m.nodes.z().data() : nullptr),
          path, "ex_put_coord");
    std::vector<std::string> names;
    for (const Block& b : m.blocks) {
      check(ex_put_elem_block(exo, b.id, b.type.c_str(), b.numElem(), b.nodesPerElem, 0), path,
            "ex_put_elem_block");
      if (b.numElem() > 0)
        check(ex_put_elem_conn(exo, b.id, b.conn.data()), path, "ex_put_elem_conn");
      names.push_back(b.name);
    }
    auto pointers = namePointers(names);
    check(ex_put_names(exo, EX_ELEM_BLOCK, pointers.data()), path, "ex_put_names");
    putVariables(exo, path, m);
  } catch (...) {
    ex_close(exo);
    throw;
  }
  check(ex_close(exo), path, "ex_close");
  return path;
}

// Corners of the box [x0,x1]x[y0,y1]x[z0,z1] in Exodus (= VTK) hexahedron order.
std::array<std::array<double, 3>, 8> boxCorners(double x0, double y0, double z0, double x1,
                                                double y1, double z1) {
  return {{{x0, y0, z0},
           {x1, y0, z0},
           {x1, y1, z0},
           {x0, y1, z0},
           {x0, y0, z1},
           {x1, y0, z1},
           {x1, y1, z1},
           {x0, y1, z1}}};
}

void addHex(Nodes& n, Block& b, double x0, double y0, double z0) {
  for (const auto& c : boxCorners(x0, y0, z0, x0 + 1, y0 + 1, z0 + 1))
    b.conn.push_back(n.at(c[0], c[1], c[2]));
}

// HEX20: corners, then mid-edge nodes of the bottom edges, the vertical edges, the top edges.
void addHex20(Nodes& n, Block& b, double x0, double y0, double z0) {
  const auto c = boxCorners(x0, y0, z0, x0 + 1, y0 + 1, z0 + 1);
  for (const auto& p : c) b.conn.push_back(n.at(p[0], p[1], p[2]));
  const int edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {1, 5},
                            {2, 6}, {3, 7}, {4, 5}, {5, 6}, {6, 7}, {7, 4}};
  for (const auto& e : edges)
    b.conn.push_back(n.at((c[e[0]][0] + c[e[1]][0]) / 2, (c[e[0]][1] + c[e[1]][1]) / 2,
                          (c[e[0]][2] + c[e[1]][2]) / 2));
}

// The unit cube at (x0,y0,z0) as 6 tetrahedra around its diagonal (Kuhn), mixed orientations.
void addKuhnTets(Nodes& n, Block& b, double x0, double y0, double z0) {
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& p : perms) {
    double q[3] = {x0, y0, z0};
    b.conn.push_back(n.at(q[0], q[1], q[2]));
    for (int k = 0; k < 3; ++k) {
      q[p[k]] += 1;
      b.conn.push_back(n.at(q[0], q[1], q[2]));
    }
  }
}

// The unit cube at (x0,y0,z0) as two wedges (triangles in z).
void addWedges(Nodes& n, Block& b, double x0, double y0, double z0) {
  const double tris[2][3][2] = {{{0, 0}, {1, 0}, {1, 1}}, {{0, 0}, {1, 1}, {0, 1}}};
  for (const auto& t : tris)
    for (double dz : {0.0, 1.0})
      for (const auto& p : t) b.conn.push_back(n.at(x0 + p[0], y0 + p[1], z0 + dz));
}

double blocksNodal(int var, int step, double x, double y, double z) {
  switch (var) {
    case 0:
      return x + 2 * y + 3 * z + 10 * step;  // temp
    case 1:
      return y;  // vel_x
    case 2:
      return -x;  // vel_y
    default:
      return step;  // vel_z
  }
}

double blocksElem(int var, int step, int blockId, int e, double) {
  return var == 0 ? 10.0 * blockId + e + 1000.0 * step : blockId + 0.25 * step;
}

// blocks.exo, or the same as a netCDF-4 (HDF5) file with 64-bit integers (blocks-nc4.exo).
std::string writeBlocks(const std::string& folder, bool netcdf4) {
  ExodusModel m;
  Nodes& n = m.nodes;
  Block hexes{10, "hexes", "HEX8", 8, {}}, tets{20, "tets", "tetra4", 4, {}},
      wedges{30, "prisms", "WEDGE6", 6, {}}, pyramid{40, "pyramid", "PYRAMID", 5, {}},
      quadratic{50, "quadratic", "HEX20", 20, {}}, skin{60, "skin", "SHELL4", 4, {}},
      edge{70, "edge", "BAR2", 2, {}};
  addHex(n, hexes, 0, 0, 0);
  addHex(n, hexes, 1, 0, 0);
  addKuhnTets(n, tets, 1, 0, 1);
  addWedges(n, wedges, 2, 0, 0);
  for (const auto& p : std::vector<std::array<double, 3>>{
           {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, {0.5, 0.5, 1.5}})
    pyramid.conn.push_back(n.at(p[0], p[1], p[2]));
  addHex20(n, quadratic, 0, 1, 0);
  for (double x0 : {0.0, 1.0})
    for (const auto& p : std::vector<std::array<double, 2>>{{0, 0}, {1, 0}, {1, 1}, {0, 1}})
      skin.conn.push_back(n.at(x0 + p[0], p[1], 0));
  edge.conn = {n.at(0, 0, 0), n.at(1, 0, 0)};
  m.blocks = {hexes, tets, wedges, pyramid, quadratic, skin, edge};
  m.times = {0.0, 0.5, 1.25};
  m.nodalVars = {"temp", "vel_x", "vel_y", "vel_z"};
  m.elemVars = {"pressure", "stress"};
  m.truth = {{1, 1}, {1, 0}, {1, 1}, {1, 1}, {1, 1}, {1, 1}, {1, 1}};
  m.nodal = &blocksNodal;
  m.elem = &blocksElem;
  if (netcdf4) return write(folder + "/blocks-nc4.exo", m, EX_NETCDF4 | EX_ALL_INT64_DB);
  return write(folder + "/blocks.exo", m);
}

double decompNodal(int, int step, double x, double y, double z) {
  return x + 2 * y + 3 * z + step;
}

double decompElem(int, int step, int, int, double rank) {
  return rank + 10.0 * step;
}

// The box [0,3]x[0,2]x[0,2] of unit hexahedra cut in x into 3 files, as a decomposer writes
// them: each file has its own nodes (those on a cut are in both files, at equal coordinates) and
// every block of the mesh, empty where the file has none of its elements.
std::vector<std::string> writeDecomposed(const std::string& folder) {
  std::vector<std::string> files;
  for (int rank = 0; rank < 3; ++rank) {
    ExodusModel m;
    Block hexes{1, "hexes", "HEX8", 8, {}}, wedges{2, "wedges", "WEDGE6", 6, {}};
    for (int z = 0; z < 2; ++z)
      for (int y = 0; y < 2; ++y) {
        if (rank == 2 && z == 1)
          addWedges(m.nodes, wedges, rank, y, z);
        else
          addHex(m.nodes, hexes, rank, y, z);
      }
    m.blocks = {hexes, wedges};
    m.times = {1.0, 2.0};
    m.nodalVars = {"temp"};
    m.elemVars = {"rank"};
    m.truth = {{1}, {1}};
    m.nodal = &decompNodal;
    m.elem = &decompElem;
    m.extra = rank;
    files.push_back(write(folder + "/decomp.e.3." + std::to_string(rank), m));
  }
  return files;
}

std::string writeFlat(const std::string& folder) {
  ExodusModel m;
  m.numDim = 2;
  Block quads{1, "quads", "QUAD4", 4, {}};
  for (const auto& p : std::vector<std::array<double, 2>>{{0, 0}, {1, 0}, {1, 1}, {0, 1}})
    quads.conn.push_back(m.nodes.at(p[0], p[1], 0));
  m.blocks = {quads};
  return write(folder + "/flat2d.exo", m);
}

std::string writeBadConnectivity(const std::string& folder) {
  ExodusModel m;
  Block hexes{7, "broken", "HEX8", 8, {}};
  addHex(m.nodes, hexes, 0, 0, 0);
  hexes.conn[5] = 99;  // 8 nodes in the file
  m.blocks = {hexes};
  return write(folder + "/badconn.exo", m);
}

}  // namespace

std::vector<std::string> writeExodusFiles(const std::string& folder) {
  std::vector<std::string> files{writeBlocks(folder, false), writeBlocks(folder, true)};
  for (std::string& f : writeDecomposed(folder)) files.push_back(std::move(f));
  files.push_back(writeFlat(folder));
  files.push_back(writeBadConnectivity(folder));
  return files;
}

}  // namespace sm::test
