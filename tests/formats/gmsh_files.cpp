// Test files written by gmsh itself (its C++ API, libgmsh 4.8): .msh 4.1 ASCII and binary,
// partitioned, second-order and mixed-element meshes with node and element data over time steps,
// and .su2 files from gmsh's SU2 writer. Gmsh cannot write a multi-zone .su2 (NZONE/IZONE), so
// that one is written here as text, two zones of one tetrahedron-split cube each.
#include <gmsh.h>

#include <array>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "format_files.h"

// libgmsh 4.8 frees with `delete` what it allocated with `new[]` while it builds a view's
// interpolation for second-order prisms (ClosureGen::getFaceClosurePrism): AddressSanitizer's
// default would abort every program that links these writers (the sanitizer and fuzz builds)
// inside gmsh. Defaults only: ASAN_OPTIONS given in the environment still apply on top.
extern "C" const char* __asan_default_options() {
  return "alloc_dealloc_mismatch=0";
}

namespace sm::test {
namespace {

// Point field values the tests recompute from the coordinates: temperature step k = x+2y+3z+k.
double temperature(double x, double y, double z, int step) {
  return x + 2 * y + 3 * z + step;
}

void setFormat(bool binary) {
  gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
  gmsh::option::setNumber("Mesh.Binary", binary ? 1 : 0);
  gmsh::option::setNumber("Mesh.SaveAll", 1);
  // Views appended without the mesh again (gmsh's default repeats $Nodes and $Elements per view).
  gmsh::option::setNumber("PostProcessing.SaveMesh", 0);
}

// Three views on the current model: "temperature" (3 steps, times 0, 0.5, 1), "velocity" (a
// vector, 1 step) on the nodes, and "pressure" (2 steps, element tag + step) on the 3D elements.
std::vector<int> addViews() {
  std::vector<std::size_t> nodeTags;
  std::vector<double> xyz, uvw;
  gmsh::model::mesh::getNodes(nodeTags, xyz, uvw, -1, -1, false, false);
  const std::string model = [] {
    std::string name;
    gmsh::model::getCurrent(name);
    return name;
  }();
  int temp = gmsh::view::add("temperature");
  for (int k = 0; k < 3; ++k) {
    std::vector<double> v(nodeTags.size());
    for (size_t i = 0; i < v.size(); ++i)
      v[i] = temperature(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2], k);
    gmsh::view::addHomogeneousModelData(temp, k, model, "NodeData", nodeTags, v, 0.5 * k, 1);
  }
  int vel = gmsh::view::add("velocity");
  gmsh::view::addHomogeneousModelData(vel, 0, model, "NodeData", nodeTags, xyz, 0., 3);
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> elemTags, elemNodes;
  gmsh::model::mesh::getElements(types, elemTags, elemNodes, 3);
  std::vector<std::size_t> cells;
  for (const auto& t : elemTags) cells.insert(cells.end(), t.begin(), t.end());
  int pres = gmsh::view::add("pressure");
  for (int k = 0; k < 2; ++k) {
    std::vector<double> v(cells.size());
    for (size_t i = 0; i < v.size(); ++i) v[i] = double(cells[i]) + k;
    gmsh::view::addHomogeneousModelData(pres, k, model, "ElementData", cells, v, 0.5 * k, 1);
  }
  return {temp, vel, pres};
}

std::string writeMesh(const std::string& path, bool binary, const std::vector<int>& views) {
  setFormat(binary);
  gmsh::write(path);
  for (int v : views) gmsh::view::write(v, path, true);
  return path;
}

void removeViews(const std::vector<int>& views) {
  for (int v : views) gmsh::view::remove(v);
}

// The unit cube in tetrahedra (element size 0.5).
void tetBox() {
  gmsh::model::add("box");
  gmsh::model::occ::addBox(0, 0, 0, 1, 1, 1);
  gmsh::model::occ::synchronize();
  gmsh::option::setNumber("Mesh.MeshSizeMax", 0.5);
  gmsh::model::mesh::generate(3);
}

// Two unit squares side by side, one in quads and one in triangles, extruded in 2 layers with
// recombination: hexahedra beside wedges.
void mixedSlab() {
  gmsh::model::add("mixed");
  int p[6];
  const double xy[6][2] = {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {1, 1}, {0, 1}};
  for (int i = 0; i < 6; ++i) p[i] = gmsh::model::geo::addPoint(xy[i][0], xy[i][1], 0, 0.5);
  auto line = [&](int a, int b) { return gmsh::model::geo::addLine(p[a], p[b]); };
  int l01 = line(0, 1), l12 = line(1, 2), l23 = line(2, 3), l34 = line(3, 4), l45 = line(4, 5),
      l50 = line(5, 0), l14 = line(1, 4);
  int quads =
      gmsh::model::geo::addPlaneSurface({gmsh::model::geo::addCurveLoop({l01, l14, l45, l50})});
  int tris =
      gmsh::model::geo::addPlaneSurface({gmsh::model::geo::addCurveLoop({l12, l23, l34, -l14})});
  for (int l : {l01, l14, l45, l50}) gmsh::model::geo::mesh::setTransfiniteCurve(l, 3);
  gmsh::model::geo::mesh::setTransfiniteSurface(quads);
  gmsh::model::geo::mesh::setRecombine(2, quads);
  gmsh::vectorpair out;
  gmsh::model::geo::extrude({{2, quads}, {2, tris}}, 0, 0, 1, out, {2}, {}, true);
  gmsh::model::geo::synchronize();
  gmsh::model::mesh::generate(3);
}

// A hexahedron, a pyramid on its top face and a tetrahedron on a pyramid face, added by hand on a
// discrete volume: what gmsh writes for pyramids without a meshing algorithm that makes them.
void pyramidStack() {
  gmsh::model::add("stack");
  const int vol = gmsh::model::addDiscreteEntity(3);
  const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0,   1,   0,   0,   0,   1,
                                   1, 0, 1, 1, 1, 1, 0, 1, 1, 0.5, 0.5, 1.6, 1.2, 0.4, 1.6};
  std::vector<std::size_t> nodes(10);
  for (size_t i = 0; i < nodes.size(); ++i) nodes[i] = i + 1;
  gmsh::model::mesh::addNodes(3, vol, nodes, xyz);
  gmsh::model::mesh::addElements(3, vol, {5, 7, 4}, {{1}, {2}, {3}},
                                 {{1, 2, 3, 4, 5, 6, 7, 8}, {5, 6, 7, 8, 9}, {6, 7, 9, 10}});
}

std::string writeZonesSu2(const std::string& path) {
  std::ofstream f(path);
  f << "% two zones, written by hand: gmsh writes single-zone .su2 files only\nNZONE= 2\n";
  for (int z = 0; z < 2; ++z) {
    f << "\nIZONE= " << z + 1
      << "\nNDIME= 3\n% a cube in 5 tetrahedra (point i at x = bit 0, y = bit 1, z = bit 2), then "
         "a face\nNELEM= 6\n";
    const int tets[5][4] = {{0, 1, 2, 4}, {3, 2, 1, 7}, {5, 1, 4, 7}, {6, 4, 2, 7}, {1, 2, 4, 7}};
    for (int e = 0; e < 5; ++e)
      f << "10 " << tets[e][0] << " " << tets[e][1] << " " << tets[e][2] << " " << tets[e][3] << " "
        << e << "\n";
    f << "5 0 1 2 5\nNPOIN= 8\n";
    for (int i = 0; i < 8; ++i)
      f << z + (i & 1) << " " << (i >> 1 & 1) << " " << (i >> 2 & 1) << " " << i << "\n";
    f << "NMARK= 1\nMARKER_TAG= bottom\nMARKER_ELEMS= 1\n9 0 1 2 3\n";
  }
  if (!f) throw std::runtime_error("cannot write " + path);
  return path;
}

}  // namespace

std::vector<std::string> writeGmshFiles(const std::string& folder) {
  const std::string d = folder + "/";
  std::vector<std::string> files;
  gmsh::initialize();
  gmsh::option::setNumber("General.Terminal", 0);
  try {
    tetBox();
    std::vector<int> views = addViews();
    files.push_back(writeMesh(d + "box.msh", false, views));
    files.push_back(writeMesh(d + "box-binary.msh", true, views));
    gmsh::write(d + "box.su2");
    files.push_back(d + "box.su2");
    removeViews(views);
    gmsh::model::mesh::setOrder(2);
    files.push_back(writeMesh(d + "box-order2.msh", false, {}));
    gmsh::model::mesh::setOrder(1);

    gmsh::option::setNumber("Mesh.PartitionCreateTopology", 1);
    gmsh::option::setNumber("Mesh.PartitionCreatePhysicals", 0);
    gmsh::model::mesh::partition(3);
    views = addViews();
    files.push_back(writeMesh(d + "box-part.msh", false, views));
    files.push_back(writeMesh(d + "box-part-binary.msh", true, views));
    removeViews(views);

    mixedSlab();
    gmsh::write(d + "mixed.su2");
    files.push_back(d + "mixed.su2");
    views = addViews();
    files.push_back(writeMesh(d + "mixed.msh", false, views));
    removeViews(views);
    gmsh::model::mesh::setOrder(2);
    views = addViews();
    files.push_back(writeMesh(d + "mixed-order2.msh", true, views));
    removeViews(views);

    pyramidStack();
    files.push_back(writeMesh(d + "stack.msh", false, {}));
    gmsh::write(d + "stack.su2");
    files.push_back(d + "stack.su2");
  } catch (...) {
    gmsh::finalize();
    throw;
  }
  gmsh::finalize();
  files.push_back(writeZonesSu2(d + "zones.su2"));
  return files;
}

}  // namespace sm::test

namespace sm::test {

// {dimension, nodes, primary nodes} of gmsh's element types 1 to 140 ({-1, 0, 0} where gmsh
// knows none), from gmsh itself: what the reader's own table must say.
std::vector<std::array<int, 3>> gmshElementTable() {
  std::vector<std::array<int, 3>> out;
  gmsh::initialize();
  gmsh::option::setNumber("General.Terminal", 0);
  for (int type = 1; type <= 140; ++type) {
    std::string name;
    int dim = 0, order = 0, nodes = 0, primary = 0;
    std::vector<double> coords;
    try {
      gmsh::model::mesh::getElementProperties(type, name, dim, order, nodes, coords, primary);
      out.push_back({dim, nodes, primary});
    } catch (...) {
      out.push_back({-1, 0, 0});
    }
  }
  gmsh::finalize();
  return out;
}

}  // namespace sm::test
