#include "gen/boundary_layer.h"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "common/check.h"
#include "gen/gmsh_session.h"

namespace sm::gen {
namespace {

using mesh::CellType;

// Cumulative heights of the layers. Positive heights grow the layer along the face normals, which
// meshWall points out of the body.
std::vector<double> layerHeights(double thickness) {
  const double first = thickness * (kLayerGrowth - 1) / (std::pow(kLayerGrowth, kLayerCount) - 1);
  std::vector<double> heights;
  double h = 0, step = first;
  for (int i = 0; i < kLayerCount; ++i, step *= kLayerGrowth) heights.push_back(h += step);
  return heights;
}

// Extrudes and meshes the layer in a new model; returns the surfaces of its outer side.
std::vector<int> meshLayer(const WallMesh& wall, double thickness) {
  gmsh::model::add("layer");
  const int wallTag = gmsh::model::addDiscreteEntity(2);
  gmsh::model::mesh::addNodes(2, wallTag, wall.nodeTags, wall.coords);
  if (!wall.triangles.empty()) gmsh::model::mesh::addElementsByType(wallTag, 2, {}, wall.triangles);
  if (!wall.quads.empty()) gmsh::model::mesh::addElementsByType(wallTag, 3, {}, wall.quads);
  gmsh::option::setNumber("Geometry.ExtrudeReturnLateralEntities", 0);
  gmsh::vectorpair extruded;
  gmsh::model::geo::extrudeBoundaryLayer({{2, wallTag}}, extruded, std::vector<int>(kLayerCount, 1),
                                         layerHeights(thickness), /*recombine=*/true);
  gmsh::model::geo::synchronize();
  // The outer side is the layer's boundary less the wall (found this way rather than by position
  // in `extruded`, whose layout depends on the number of lateral entities).
  gmsh::vectorpair volumes, boundary;
  for (const auto& dt : extruded)
    if (dt.first == 3) volumes.push_back(dt);
  gmsh::model::getBoundary(volumes, boundary, true, false, false);
  std::vector<int> outer;
  for (const auto& [dim, tag] : boundary)
    if (dim == 2 && std::abs(tag) != wallTag) outer.push_back(std::abs(tag));
  if (outer.empty()) throw GmshError("extruding the boundary layer", "it has no outer surface");
  gmsh::model::mesh::generate(3);
  return outer;
}

// gmsh node tags of the layer model -> points of the assembly, added on first use.
class NodeMap {
 public:
  explicit NodeMap(VolumeAssembly& a) : a_(a) {
    std::vector<std::size_t> tags;
    std::vector<double> coords, parametric;
    gmsh::model::mesh::getNodes(tags, coords, parametric, -1, -1, false, false);
    for (size_t i = 0; i < tags.size(); ++i)
      position_[tags[i]] = {coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]};
  }
  uint32_t operator()(std::size_t tag) {
    auto [it, added] = index_.try_emplace(tag, 0);
    if (added) it->second = a_.addPoint(position_.at(tag));
    return it->second;
  }

 private:
  VolumeAssembly& a_;
  std::unordered_map<std::size_t, glm::dvec3> position_;
  std::unordered_map<std::size_t, uint32_t> index_;
};

// A quad as a key: its sorted ids.
struct QuadKeyHash {
  size_t operator()(const Quad& q) const {
    uint64_t h = 0x9E3779B97F4A7C15ull;
    for (uint32_t id : q) h = (h ^ id) * 0x100000001B3ull;
    return size_t(h);
  }
};
Quad sorted(Quad q) {
  std::sort(q.begin(), q.end());
  return q;
}

}  // namespace

std::vector<Triangle> addBoundaryLayer(const WallMesh& wall, double thickness, VolumeAssembly& a) {
  std::vector<int> outer =
      gmshStage("extruding the boundary layer", [&] { return meshLayer(wall, thickness); });
  NodeMap node(a);

  // Wedges (gmsh prisms, whose first triangle faces the second counter-clockwise, VTK's clockwise:
  // swap 1 <-> 2 and 4 <-> 5) and hexahedra (same order in both).
  std::vector<std::array<uint32_t, 8>> hexes;
  gmshStage("reading the boundary layer", [&] {
    std::vector<std::size_t> nodes = elementNodes(6);
    for (size_t e = 0; e < nodes.size(); e += 6) {
      const uint32_t w[6] = {node(nodes[e]),     node(nodes[e + 2]), node(nodes[e + 1]),
                             node(nodes[e + 3]), node(nodes[e + 5]), node(nodes[e + 4])};
      a.addCell(CellType::Wedge, w);
    }
    nodes = elementNodes(5);
    for (size_t e = 0; e < nodes.size(); e += 8) {
      std::array<uint32_t, 8> h;
      for (int k = 0; k < 8; ++k) h[k] = node(nodes[e + k]);
      a.addCell(CellType::Hex, h);
      hexes.push_back(h);
    }
    for (int type : {4, 7})
      SM_CHECK_MSG(elementNodes(type).empty(),
                   "gmsh put element type " << type << " in the boundary layer");
  });

  // The outer side: triangles as they are, quads capped away from the hexahedron below them.
  std::vector<Triangle> surface;
  std::vector<Quad> quads;
  gmshStage("reading the boundary layer", [&] {
    for (int tag : outer) {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> elementTags, nodes;
      gmsh::model::mesh::getElements(types, elementTags, nodes, 2, tag);
      for (size_t i = 0; i < types.size(); ++i) {
        const auto& n = nodes[i];
        if (types[i] == 2)
          for (size_t e = 0; e < n.size(); e += 3)
            surface.push_back({node(n[e]), node(n[e + 1]), node(n[e + 2])});
        else if (types[i] == 3)
          for (size_t e = 0; e < n.size(); e += 4)
            quads.push_back({node(n[e]), node(n[e + 1]), node(n[e + 2]), node(n[e + 3])});
        else
          SM_CHECK_MSG(false, "unexpected element type " << types[i] << " on the boundary layer");
      }
    }
  });
  std::unordered_map<Quad, glm::dvec3, QuadKeyHash> hexCentreByFace;
  for (const auto& h : hexes) {
    glm::dvec3 centre(0.0);
    for (uint32_t v : h) centre += a.points[v] / 8.0;
    for (uint32_t f = 0; f < 6; ++f) {
      Quad q;
      for (int k = 0; k < 4; ++k) q[k] = h[mesh::faceVert(CellType::Hex, f, k)];
      hexCentreByFace[sorted(q)] = centre;
    }
  }
  std::vector<glm::dvec3> inside;
  for (const Quad& q : quads) inside.push_back(hexCentreByFace.at(sorted(q)));
  std::vector<Triangle> caps = capQuads(a, quads, inside, kCapHeightFraction);
  surface.insert(surface.end(), caps.begin(), caps.end());
  return surface;
}

}  // namespace sm::gen
