// Orienting closed triangle/quad surfaces: neighbours made to agree (a shared edge runs in opposite
// directions), then each connected component turned so that its normals point out of the volume
// it encloses. gmsh's boundary layer grows along the wall's normals, so the wall must be wound this
// way; the far field's hole surfaces are checked and wound the same way before gmsh sees them.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <queue>
#include <span>
#include <unordered_map>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "gen/gmsh_session.h"

namespace sm::gen {

// Faces as spans into the caller's arrays (flipped in place). Throws GmshError naming `stage` when
// the faces (which gmsh made) are not a closed, orientable two-manifold.
template <typename Id>
void orientOutward(std::vector<std::span<Id>>& faces, const std::function<glm::dvec3(Id)>& position,
                   const char* stage) {
  auto key = [](Id a, Id b) { return std::pair<Id, Id>(std::min(a, b), std::max(a, b)); };
  struct PairHash {
    size_t operator()(const std::pair<Id, Id>& p) const {
      return std::hash<uint64_t>()(uint64_t(p.first) * 0x9E3779B97F4A7C15ull ^ uint64_t(p.second));
    }
  };
  std::unordered_map<std::pair<Id, Id>, std::vector<uint32_t>, PairHash> edges;
  for (uint32_t f = 0; f < faces.size(); ++f)
    for (size_t k = 0; k < faces[f].size(); ++k)
      edges[key(faces[f][k], faces[f][(k + 1) % faces[f].size()])].push_back(f);
  for (const auto& [edge, list] : edges)
    if (list.size() != 2)
      throw GmshError(stage, concat("an edge is used by ", list.size(), " faces instead of 2"));

  auto runsForward = [](std::span<Id> f, Id a, Id b) {
    for (size_t k = 0; k < f.size(); ++k)
      if (f[k] == a && f[(k + 1) % f.size()] == b) return true;
    return false;
  };
  auto flip = [](std::span<Id> f) { std::reverse(f.begin() + 1, f.end()); };

  constexpr uint32_t kNone = 0xFFFFFFFFu;
  std::vector<uint32_t> component(faces.size(), kNone);
  std::vector<double> volume;
  for (uint32_t seed = 0; seed < faces.size(); ++seed) {
    if (component[seed] != kNone) continue;
    const uint32_t c = uint32_t(volume.size());
    volume.push_back(0.0);
    std::queue<uint32_t> todo;
    component[seed] = c;
    todo.push(seed);
    while (!todo.empty()) {
      const uint32_t fi = todo.front();
      todo.pop();
      std::span<Id> f = faces[fi];
      for (size_t k = 0; k < f.size(); ++k) {
        const Id a = f[k], b = f[(k + 1) % f.size()];
        const auto& pair = edges.at(key(a, b));
        const uint32_t g = pair[0] == fi ? pair[1] : pair[0];
        const bool clash = runsForward(faces[g], a, b);
        if (component[g] == kNone) {
          if (clash) flip(faces[g]);
          component[g] = c;
          todo.push(g);
        } else if (clash) {
          throw GmshError(stage, "the surface is not orientable");
        }
      }
      // Enclosed volume by the divergence theorem (a fan from vertex 0 of each face).
      const glm::dvec3 p0 = position(f[0]);
      for (size_t k = 1; k + 1 < f.size(); ++k)
        volume[c] += glm::dot(p0, glm::cross(position(f[k]), position(f[k + 1]))) / 6.0;
    }
  }
  for (uint32_t f = 0; f < faces.size(); ++f)
    if (volume[component[f]] < 0.0) flip(faces[f]);
}

}  // namespace sm::gen
