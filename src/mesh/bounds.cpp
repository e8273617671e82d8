#include "mesh/bounds.h"

#include <cmath>

#include <glm/common.hpp>

namespace sm::mesh {

void Bounds::extend(const glm::dvec3& p) {
  if (empty) {
    lo = hi = p;
    empty = false;
  } else {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
}

void Bounds::extend(const Bounds& b) {
  if (b.empty) return;
  extend(b.lo);
  extend(b.hi);
}

double Bounds::diagonal() const {
  if (empty) return 0.0;
  glm::dvec3 e = extent();
  return std::sqrt(e.x * e.x + e.y * e.y + e.z * e.z);
}

}  // namespace sm::mesh
