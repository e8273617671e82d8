#include "gen/wall_mesh.h"

#include <gmsh.h>

#include <algorithm>
#include <cstdlib>
#include <unordered_map>

#include "common/check.h"
#include "gen/gmsh_session.h"
#include "gen/surface_orientation.h"

namespace sm::gen {

WallMesh meshWall(int volume, const std::vector<int>& recombine,
                  const std::function<double(const glm::dvec3&)>& size) {
  WallMesh wall;
  gmsh::vectorpair boundary;
  gmshStage("meshing the body surface", [&] {
    gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
    gmsh::model::mesh::setSizeCallback([&size](int, int, double x, double y, double z) {
      return size({x, y, z});
    });
    gmsh::model::getBoundary({{3, volume}}, boundary, false, false, false);
    for (int s : recombine) gmsh::model::mesh::setRecombine(2, s);
    gmsh::model::mesh::generate(2);
    // Only the solid's own faces: construction leftovers (the revolved profile) are meshed too.
    for (const auto& [dim, tag] : boundary) {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> elementTags, nodeTags;
      gmsh::model::mesh::getElements(types, elementTags, nodeTags, dim, std::abs(tag));
      for (size_t i = 0; i < types.size(); ++i) {
        SM_CHECK_MSG(types[i] == 2 || types[i] == 3,
                     "unexpected gmsh surface element type " << types[i]);
        auto& out = types[i] == 2 ? wall.triangles : wall.quads;
        out.insert(out.end(), nodeTags[i].begin(), nodeTags[i].end());
      }
    }
  });
  std::vector<std::size_t> allTags;
  std::vector<double> allCoords, parametric;
  gmshStage("reading the body surface", [&] {
    gmsh::model::mesh::getNodes(allTags, allCoords, parametric, -1, -1, true, false);
  });
  std::unordered_map<std::size_t, glm::dvec3> position;
  for (size_t i = 0; i < allTags.size(); ++i)
    position[allTags[i]] = {allCoords[3 * i], allCoords[3 * i + 1], allCoords[3 * i + 2]};

  std::vector<std::span<std::size_t>> faces;
  for (size_t i = 0; i < wall.triangles.size(); i += 3) faces.push_back({&wall.triangles[i], 3});
  for (size_t i = 0; i < wall.quads.size(); i += 4) faces.push_back({&wall.quads[i], 4});
  orientOutward<std::size_t>(
      faces, [&](std::size_t tag) { return position.at(tag); }, "meshing the body surface");

  std::vector<std::size_t> used(wall.triangles);
  used.insert(used.end(), wall.quads.begin(), wall.quads.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  for (std::size_t tag : used) {
    const glm::dvec3& p = position.at(tag);
    wall.nodeTags.push_back(tag);
    wall.coords.insert(wall.coords.end(), {p.x, p.y, p.z});
  }
  return wall;
}

}  // namespace sm::gen
