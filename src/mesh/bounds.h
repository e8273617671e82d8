// An axis-aligned box that starts empty and grows around what it is given. Its own header so that
// modules which handle boxes only (the renderer, cameras, prepared ranks) do not include the mesh.
#pragma once

#include <glm/vec3.hpp>

namespace sm::mesh {

struct Bounds {
  glm::dvec3 lo{0.0}, hi{0.0};
  bool empty = true;
  void extend(const glm::dvec3& p);
  void extend(const Bounds& b);
  glm::dvec3 center() const { return (lo + hi) * 0.5; }
  glm::dvec3 extent() const { return hi - lo; }
  double diagonal() const;
};

}  // namespace sm::mesh
