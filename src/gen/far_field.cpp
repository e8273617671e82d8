#include "gen/far_field.h"

#include <gmsh.h>

#include <algorithm>
#include <unordered_map>

#include "common/check.h"
#include "gen/gmsh_session.h"
#include "gen/surface_orientation.h"

namespace sm::gen {
namespace {

namespace geo = gmsh::model::geo;

// A closed surface as a discrete gmsh surface and a surface loop. Assembly point i is gmsh node
// i + 1 (gmsh tags start at 1). The surface is checked (closed two-manifold) and wound consistently
// first: a broken layer or cap would otherwise surface as an obscure error deep in gmsh.
int addHoleSurface(const VolumeAssembly& a, std::vector<Triangle> triangles,
                   std::vector<char>& passed) {
  std::vector<std::span<uint32_t>> faces;
  for (auto& t : triangles) faces.push_back(t);
  orientOutward<uint32_t>(
      faces, [&](uint32_t i) { return a.points[i]; }, "closing the far field");
  std::vector<uint32_t> ids;
  for (const auto& t : triangles) ids.insert(ids.end(), t.begin(), t.end());
  std::vector<std::size_t> elementNodes(ids.begin(), ids.end());
  for (auto& n : elementNodes) ++n;
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::vector<std::size_t> tags;
  std::vector<double> coords;
  for (uint32_t i : ids) {
    tags.push_back(std::size_t(i) + 1);
    coords.insert(coords.end(), {a.points[i].x, a.points[i].y, a.points[i].z});
    passed[std::size_t(i) + 1] = 1;
  }
  const int tag = gmsh::model::addDiscreteEntity(2);
  gmsh::model::mesh::addNodes(2, tag, tags, coords);
  gmsh::model::mesh::addElementsByType(tag, 2, {}, elementNodes);
  return geo::addSurfaceLoop({tag});
}

int addBoxLoop(const Box& box) {
  int p[8];
  for (int b = 0; b < 8; ++b)
    p[b] = geo::addPoint(b & 1 ? box.hi.x : box.lo.x, b & 2 ? box.hi.y : box.lo.y,
                         b & 4 ? box.hi.z : box.lo.z);
  // line[b][axis]: from corner b (which lacks that axis bit) along the axis.
  int line[8][3] = {};
  for (int b = 0; b < 8; ++b)
    for (int axis = 0; axis < 3; ++axis)
      if (!(b & (1 << axis))) line[b][axis] = geo::addLine(p[b], p[b | (1 << axis)]);
  std::vector<int> faces;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
      const int c = side << axis, cu = c | (1 << u), cv = c | (1 << v);
      const int loop =
          geo::addCurveLoop({line[c][u], line[cu][v], -line[cv][u], -line[c][v]}, -1, true);
      faces.push_back(geo::addPlaneSurface({loop}));
    }
  return geo::addSurfaceLoop(faces);
}

}  // namespace

void addFarField(VolumeAssembly& a, const Box& box, const std::vector<std::vector<Triangle>>& holes,
                 const std::function<double(const glm::dvec3&)>& size) {
  std::vector<char> passed(a.points.size() + 1, 0);
  gmshStage("meshing the far field", [&] {
    gmsh::model::add("far field");
    std::vector<int> loops = {addBoxLoop(box)};
    // The model must know the box's surfaces before discrete ones are added, or a discrete surface
    // takes a tag that a box surface then claims.
    geo::synchronize();
    for (const auto& hole : holes) loops.push_back(addHoleSurface(a, hole, passed));
    geo::addVolume(loops);
    geo::synchronize();
    gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
    gmsh::model::mesh::setSizeCallback([&size](int, int, double x, double y, double z) {
      return size({x, y, z});
    });
    gmsh::model::mesh::generate(3);
  });

  gmshStage("reading the far field", [&] {
    std::vector<std::size_t> tags;
    std::vector<double> coords, parametric;
    gmsh::model::mesh::getNodes(tags, coords, parametric, -1, -1, false, false);
    std::unordered_map<std::size_t, size_t> position;
    for (size_t i = 0; i < tags.size(); ++i) {
      position[tags[i]] = i;
      // Tags of the surfaces' points must still be theirs (gmsh renumbers unless told not to).
      if (tags[i] < passed.size() && passed[tags[i]])
        SM_CHECK(a.points[tags[i] - 1] ==
                 glm::dvec3(coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]));
    }
    std::unordered_map<std::size_t, uint32_t> added;
    auto point = [&](std::size_t tag) -> uint32_t {
      if (tag < passed.size() && passed[tag]) return uint32_t(tag - 1);
      auto [it, isNew] = added.try_emplace(tag, 0);
      if (isNew) {
        const double* c = &coords[3 * position.at(tag)];
        it->second = a.addPoint({c[0], c[1], c[2]});
      }
      return it->second;
    };
    const std::vector<std::size_t> nodes = elementNodes(4);
    for (size_t e = 0; e < nodes.size(); e += 4) {
      const uint32_t tet[4] = {point(nodes[e]), point(nodes[e + 1]), point(nodes[e + 2]),
                               point(nodes[e + 3])};
      a.addCell(mesh::CellType::Tet, tet);
    }
    for (int type : {5, 6, 7})
      SM_CHECK_MSG(elementNodes(type).empty(),
                   "gmsh put element type " << type << " in the far field");
  });
}

}  // namespace sm::gen
