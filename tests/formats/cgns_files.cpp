// CGNS test files written with libcgns's own writer (the mid-level library, as solvers use it).
//   mixed.cgns   base 'Base': zone 'A' (unstructured, 20 vertices on a 5x2x2 lattice: a HEXA_8
//                section, a MIXED section of 3 PYRA_5 and 2 PENTA_6, a TETRA_4 section of 6, and a
//                QUAD_4 boundary section 'Wall' of 4), zone 'B' (structured 3x3x2, 4 hexahedra);
//                base 'Base2': zone 'C' (HEXA_20, TETRA_10, PENTA_15, one each).
//                Every zone: Vertex field Temperature = x + 2y + 3z + 10 s and CellCenter field
//                Pressure = (volume element index in the zone) + 100 s, for steps s = 0, 1, 2 at
//                times 0, 0.5, 1.5 (BaseIterativeData, ZoneIterativeData FlowSolutionPointers;
//                the Vertex solutions are written in the order FS2, FS0, FS1).
//   poly.cgns    two unit cubes as NFACE_n polyhedra over 11 NGON_n faces; Temperature as above.
//   higher.cgns  PYRA_13, PYRA_14, PENTA_18, HEXA_27 (one each; VTK 9.1 reads no pyramid of
//                these, so they are not in mixed.cgns), and a 2D base 'Surface' of one QUAD_4.
//   bad-vertex.cgns  a TETRA_4 naming vertex 99 of 4.
//   bad-field.cgns   a Vertex field of 3 values on 4 vertices.
#include <cgnslib.h>

#include <array>
#include <stdexcept>
#include <string>

#include "format_files.h"

namespace sm::test {
namespace {

using P = std::array<double, 3>;

void ok(int rc, const char* what) {
  if (rc != CG_OK) throw std::runtime_error(std::string(what) + ": " + cg_get_error());
}

struct ZoneData {
  std::vector<P> points;
  std::vector<cgsize_t> nodes;  // scratch
  int add(const P& p) {
    points.push_back(p);
    return int(points.size());
  }
};

// The 8 corners (CGNS order) of the unit cube at x0 of a lattice nx x 2 x 2 (1-based ids).
std::array<cgsize_t, 8> cube(int x0, int nx) {
  auto id = [&](int i, int j, int k) { return cgsize_t(1 + i + nx * (j + 2 * k)); };
  return {id(x0, 0, 0), id(x0 + 1, 0, 0), id(x0 + 1, 1, 0), id(x0, 1, 0),
          id(x0, 0, 1), id(x0 + 1, 0, 1), id(x0 + 1, 1, 1), id(x0, 1, 1)};
}

std::vector<P> lattice(int nx, double x0) {
  std::vector<P> p;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < nx; ++i) p.push_back({x0 + i, double(j), double(k)});
  return p;
}

void writeCoords(int fn, int b, int z, const std::vector<P>& p) {
  for (int d = 0; d < 3; ++d) {
    std::vector<double> c;
    for (const P& q : p) c.push_back(q[size_t(d)]);
    const char* names[3] = {"CoordinateX", "CoordinateY", "CoordinateZ"};
    int C = 0;
    ok(cg_coord_write(fn, b, z, RealDouble, names[d], c.data(), &C), "cg_coord_write");
  }
}

const char* kTimes[3] = {"FS0", "FS1", "FS2"};

// Temperature at the points and Pressure per volume element, 3 steps, with iterative data.
void writeSolutions(int fn, int b, int z, const std::vector<P>& p, int cells, bool cellData) {
  for (int s : {2, 0, 1}) {
    std::vector<double> t;
    for (const P& q : p) t.push_back(q[0] + 2 * q[1] + 3 * q[2] + 10 * s);
    int S = 0, F = 0;
    ok(cg_sol_write(fn, b, z, kTimes[s], Vertex, &S), "cg_sol_write");
    ok(cg_field_write(fn, b, z, S, RealDouble, "Temperature", t.data(), &F), "cg_field_write");
  }
  for (int s = 0; cellData && s < 3; ++s) {
    std::vector<float> v;
    for (int c = 0; c < cells; ++c) v.push_back(float(c + 100 * s));
    int S = 0, F = 0;
    const std::string name = "CC" + std::to_string(s);
    ok(cg_sol_write(fn, b, z, name.c_str(), CellCenter, &S), "cg_sol_write");
    ok(cg_field_write(fn, b, z, S, RealSingle, "Pressure", v.data(), &F), "cg_field_write");
  }
  ok(cg_ziter_write(fn, b, z, "ZoneIterativeData"), "cg_ziter_write");
  ok(cg_goto(fn, b, "Zone_t", z, "ZoneIterativeData_t", 1, "end"), "cg_goto");
  // 32 blank-padded characters per name, no terminator (snprintf's last one needs a byte more).
  char names[3 * 32 + 1];
  for (int s = 0; s < 3; ++s) snprintf(names + 32 * s, 33, "%-32s", kTimes[s]);
  const cgsize_t dims[2] = {32, 3};
  ok(cg_array_write("FlowSolutionPointers", Character, 2, dims, names), "cg_array_write");
}

void writeTimes(int fn, int b) {
  ok(cg_simulation_type_write(fn, b, TimeAccurate), "cg_simulation_type_write");
  ok(cg_biter_write(fn, b, "TimeIterValues", 3), "cg_biter_write");
  ok(cg_goto(fn, b, "BaseIterativeData_t", 1, "end"), "cg_goto");
  const double t[3] = {0, 0.5, 1.5};
  const cgsize_t n = 3;
  ok(cg_array_write("TimeValues", RealDouble, 1, &n, t), "cg_array_write");
}

int section(int fn, int b, int z, const char* name, ElementType_t type, int start, int end,
            const std::vector<cgsize_t>& ids) {
  int S = 0;
  ok(cg_section_write(fn, b, z, name, type, start, end, 0, ids.data(), &S), "cg_section_write");
  return S;
}

void zoneA(int fn, int b) {
  const std::vector<P> p = lattice(5, 0);
  const cgsize_t size[3] = {20, 12, 0};
  int z = 0;
  ok(cg_zone_write(fn, b, "A", size, Unstructured, &z), "cg_zone_write");
  writeCoords(fn, b, z, p);
  const auto h = cube(0, 5);
  section(fn, b, z, "Hex", HEXA_8, 1, 1, {h.begin(), h.end()});
  // Cube 1: three pyramids with apex at corner 6; cube 2: two prisms.
  const auto c = cube(1, 5), d = cube(2, 5);
  std::vector<cgsize_t> mixed = {PYRA_5, c[0],    c[1],    c[2], c[3],   c[6], PYRA_5, c[0],
                                 c[4],   c[5],    c[1],    c[6], PYRA_5, c[0], c[3],   c[7],
                                 c[4],   c[6],    PENTA_6, d[0], d[1],   d[2], d[4],   d[5],
                                 d[6],   PENTA_6, d[0],    d[2], d[3],   d[4], d[6],   d[7]};
  const cgsize_t offsets[6] = {0, 6, 12, 18, 25, 32};  // CGNS 3.4: MIXED has offsets
  int S = 0;
  ok(cg_poly_section_write(fn, b, z, "Mixed", MIXED, 2, 6, 0, mixed.data(), offsets, &S),
     "cg_poly_section_write");
  const auto e = cube(3, 5);
  const int kuhn[6][2] = {{1, 2}, {2, 3}, {3, 7}, {7, 4}, {4, 5}, {5, 1}};
  std::vector<cgsize_t> tets;
  for (const auto& k : kuhn)
    tets.insert(tets.end(), {e[0], e[size_t(k[0])], e[size_t(k[1])], e[6]});
  section(fn, b, z, "Tets", TETRA_4, 7, 12, tets);
  std::vector<cgsize_t> wall;
  for (int x = 0; x < 4; ++x) {
    const auto q = cube(x, 5);
    wall.insert(wall.end(), {q[0], q[3], q[2], q[1]});
  }
  section(fn, b, z, "Wall", QUAD_4, 13, 16, wall);
  writeSolutions(fn, b, z, p, 12, true);
}

void zoneB(int fn, int b) {
  const cgsize_t size[9] = {3, 3, 2, 2, 2, 1, 0, 0, 0};
  int z = 0;
  ok(cg_zone_write(fn, b, "B", size, Structured, &z), "cg_zone_write");
  std::vector<P> p;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) p.push_back({5.0 + i, 0.5 * j, double(k)});
  writeCoords(fn, b, z, p);
  writeSolutions(fn, b, z, p, 4, true);
}

// An element of `type` on `corners` (points added to `zone`), its edge midpoints (CGNS order)
// and, for the types with face or volume nodes, further points inside it.
std::vector<cgsize_t> element(ZoneData& zone, const std::vector<P>& corners,
                              const std::vector<std::array<int, 2>>& edges, int npe) {
  std::vector<cgsize_t> ids;
  P centre{0, 0, 0};
  for (const P& c : corners) {
    ids.push_back(zone.add(c));
    for (int d = 0; d < 3; ++d) centre[size_t(d)] += c[size_t(d)] / double(corners.size());
  }
  for (const auto& e : edges) {
    const P& a = corners[size_t(e[0])];
    const P& b = corners[size_t(e[1])];
    ids.push_back(zone.add({(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2}));
  }
  for (int k = int(ids.size()); k < npe; ++k)
    ids.push_back(zone.add({centre[0], centre[1], centre[2] + 0.01 * k}));
  return ids;
}

std::vector<P> unitCube(double x0) {
  return {{x0, 0, 0}, {x0 + 1, 0, 0}, {x0 + 1, 1, 0}, {x0, 1, 0},
          {x0, 0, 1}, {x0 + 1, 0, 1}, {x0 + 1, 1, 1}, {x0, 1, 1}};
}

const std::vector<std::array<int, 2>> kHexEdges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {1, 5},
                                                   {2, 6}, {3, 7}, {4, 5}, {5, 6}, {6, 7}, {7, 4}};
const std::vector<std::array<int, 2>> kTetEdges = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
const std::vector<std::array<int, 2>> kPentaEdges = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 4},
                                                     {2, 5}, {3, 4}, {4, 5}, {5, 3}};
const std::vector<std::array<int, 2>> kPyraEdges = {{0, 1}, {1, 2}, {2, 3}, {3, 0},
                                                    {0, 4}, {1, 4}, {2, 4}, {3, 4}};

// One element of each type, each on its own unit cube along x from x0, in one zone.
void higherOrderZone(int fn, int b, const char* name, double x0,
                     const std::vector<ElementType_t>& types, bool solutions) {
  ZoneData zone;
  std::vector<std::vector<cgsize_t>> elements;
  for (size_t i = 0; i < types.size(); ++i) {
    const std::vector<P> c = unitCube(x0 + 2.0 * double(i));
    int npe = 0;
    cg_npe(types[i], &npe);
    switch (types[i]) {
      case HEXA_20:
      case HEXA_27:
        elements.push_back(element(zone, c, kHexEdges, npe));
        break;
      case TETRA_10:
        elements.push_back(element(zone, {c[0], c[1], c[3], c[4]}, kTetEdges, npe));
        break;
      case PENTA_15:
      case PENTA_18:
        elements.push_back(element(zone, {c[0], c[1], c[2], c[4], c[5], c[6]}, kPentaEdges, npe));
        break;
      default:  // pyramids
        elements.push_back(
            element(zone, {c[0], c[1], c[2], c[3], {c[0][0] + 0.5, 0.5, 1.0}}, kPyraEdges, npe));
    }
  }
  const cgsize_t size[3] = {cgsize_t(zone.points.size()), cgsize_t(types.size()), 0};
  int z = 0;
  ok(cg_zone_write(fn, b, name, size, Unstructured, &z), "cg_zone_write");
  writeCoords(fn, b, z, zone.points);
  for (size_t i = 0; i < types.size(); ++i)
    section(fn, b, z, cg_ElementTypeName(types[i]), types[i], int(i) + 1, int(i) + 1, elements[i]);
  if (solutions) writeSolutions(fn, b, z, zone.points, int(types.size()), true);
}

struct Open {
  int fn = 0;
  explicit Open(const std::string& path) {
    ok(cg_set_file_type(CG_FILE_HDF5), "cg_set_file_type");
    ok(cg_open(path.c_str(), CG_MODE_WRITE, &fn), "cg_open");
  }
  ~Open() { cg_close(fn); }
  int base(const char* name) {
    int b = 0;
    ok(cg_base_write(fn, name, 3, 3, &b), "cg_base_write");
    return b;
  }
};

void writeMixed(const std::string& path) {
  Open f(path);
  int b = f.base("Base");
  zoneA(f.fn, b);
  zoneB(f.fn, b);
  writeTimes(f.fn, b);
  b = f.base("Base2");
  higherOrderZone(f.fn, b, "C", 8, {HEXA_20, TETRA_10, PENTA_15}, true);
  writeTimes(f.fn, b);
}

// Faces of two cubes on a 3x2x2 lattice, each normal along +x, +y or +z.
void writePoly(const std::string& path) {
  Open f(path);
  const int b = f.base("Base");
  const cgsize_t size[3] = {12, 2, 0};
  int z = 0;
  ok(cg_zone_write(f.fn, b, "Poly", size, Unstructured, &z), "cg_zone_write");
  const std::vector<P> p = lattice(3, 0);
  writeCoords(f.fn, b, z, p);
  auto id = [](int i, int j, int k) { return cgsize_t(1 + i + 3 * (j + 2 * k)); };
  std::vector<cgsize_t> faces, offsets{0};
  auto face = [&](std::array<cgsize_t, 4> q) {
    faces.insert(faces.end(), q.begin(), q.end());
    offsets.push_back(cgsize_t(faces.size()));
  };
  for (int x = 0; x < 3; ++x) face({id(x, 0, 0), id(x, 1, 0), id(x, 1, 1), id(x, 0, 1)});  // 1-3
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x)  // 4-7: y = 0 (x = 0, 1), y = 1
      face({id(x, y, 0), id(x, y, 1), id(x + 1, y, 1), id(x + 1, y, 0)});
  for (int zz = 0; zz < 2; ++zz)
    for (int x = 0; x < 2; ++x)  // 8-11
      face({id(x, 0, zz), id(x + 1, 0, zz), id(x + 1, 1, zz), id(x, 1, zz)});
  int S = 0;
  ok(cg_poly_section_write(f.fn, b, z, "Faces", NGON_n, 1, 11, 0, faces.data(), offsets.data(), &S),
     "cg_poly_section_write");
  std::vector<cgsize_t> cells, cellOffsets{0};
  for (int c = 0; c < 2; ++c) {
    cells.insert(cells.end(), {-cgsize_t(1 + c), cgsize_t(2 + c), -cgsize_t(4 + c), cgsize_t(6 + c),
                               -cgsize_t(8 + c), cgsize_t(10 + c)});
    cellOffsets.push_back(cgsize_t(cells.size()));
  }
  ok(cg_poly_section_write(f.fn, b, z, "Cells", NFACE_n, 12, 13, 0, cells.data(),
                           cellOffsets.data(), &S),
     "cg_poly_section_write");
  std::vector<double> t;
  for (const P& q : p) t.push_back(q[0] + 2 * q[1] + 3 * q[2]);
  int F = 0;
  ok(cg_sol_write(f.fn, b, z, "Flow", Vertex, &S), "cg_sol_write");
  ok(cg_field_write(f.fn, b, z, S, RealDouble, "Temperature", t.data(), &F), "cg_field_write");
}

void writeHigher(const std::string& path) {
  Open f(path);
  higherOrderZone(f.fn, f.base("Base"), "H", 0, {PYRA_13, PYRA_14, PENTA_18, HEXA_27}, false);
  // A surface base (cell dimension 2): its zone is skipped and its cells counted.
  int b = 0, z = 0;
  ok(cg_base_write(f.fn, "Surface", 2, 3, &b), "cg_base_write");
  const cgsize_t size[3] = {4, 1, 0};
  ok(cg_zone_write(f.fn, b, "S", size, Unstructured, &z), "cg_zone_write");
  writeCoords(f.fn, b, z, {{0, 0, -1}, {1, 0, -1}, {1, 1, -1}, {0, 1, -1}});
  section(f.fn, b, z, "Quad", QUAD_4, 1, 1, {1, 2, 3, 4});
}

// One tetrahedron; `badVertex` names vertex 99, `shortField` writes 3 values for 4 vertices.
void writeBad(const std::string& path, bool badVertex, bool shortField) {
  Open f(path);
  const int b = f.base("Base");
  const cgsize_t size[3] = {4, 1, 0};
  int z = 0, S = 0;
  ok(cg_zone_write(f.fn, b, "T", size, Unstructured, &z), "cg_zone_write");
  writeCoords(f.fn, b, z, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  section(f.fn, b, z, "Tet", TETRA_4, 1, 1, {1, 2, 3, badVertex ? 99 : 4});
  ok(cg_sol_write(f.fn, b, z, "Flow", Vertex, &S), "cg_sol_write");
  const double t[4] = {1, 2, 3, 4};
  if (shortField) {
    ok(cg_goto(f.fn, b, "Zone_t", z, "FlowSolution_t", S, "end"), "cg_goto");
    const cgsize_t n = 3;
    ok(cg_array_write("Temperature", RealDouble, 1, &n, t), "cg_array_write");
  } else {
    int F = 0;
    ok(cg_field_write(f.fn, b, z, S, RealDouble, "Temperature", t, &F), "cg_field_write");
  }
}

}  // namespace

std::vector<std::string> writeCgnsFiles(const std::string& folder) {
  const std::string mixed = folder + "/mixed.cgns", poly = folder + "/poly.cgns",
                    higher = folder + "/higher.cgns", badVertex = folder + "/bad-vertex.cgns",
                    badField = folder + "/bad-field.cgns";
  writeMixed(mixed);
  writePoly(poly);
  writeHigher(higher);
  writeBad(badVertex, true, false);
  writeBad(badField, false, true);
  return {mixed, poly, higher, badVertex, badField};
}

}  // namespace sm::test
