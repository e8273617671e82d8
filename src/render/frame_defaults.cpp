#include "render/frame_defaults.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "common/error.h"
#include "mesh/element_geometry.h"

namespace sm::render {

ElementSizeSum elementSizeSum(const mesh::UnstructuredMesh& m) {
  ElementSizeSum s;
  for (mesh::CellType t : mesh::kAllCellTypes) {
    const uint32_t nv = mesh::numVerts(t);
    const auto& cells = m.cells[mesh::typeIndex(t)];
    for (size_t e = 0; e + nv <= cells.size(); e += nv) {
      double v =
          std::abs(mesh::signedVolume(t, std::span<const uint32_t>(&cells[e], nv), m.points));
      s.sum += std::cbrt(v);
      ++s.count;
    }
  }
  return s;
}

double finestStep(const glm::dvec3& eye, const mesh::Bounds& b) {
  if (b.empty) return 0.0;
  double far = 0.0;
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 corner((c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y,
                            (c & 4) ? b.hi.z : b.lo.z);
    far = std::max(far, glm::length(corner - eye));
  }
  return far * 0x1p-24;
}

void checkStep(double dt, const glm::dvec3& eye, const mesh::Bounds& b, const char* option) {
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw Error(option, ": the sample distance must be positive and finite, not ", dt);
  const double finest = finestStep(eye, b);
  if (dt < finest)
    throw Error(option, ": ", dt,
                " is finer than float distances along a ray resolve in this view ",
                "(the data reaches ", finest * 0x1p24, " from the eye); use at least ", finest);
}

void checkStepNotBeyondData(double dt, const mesh::Bounds& b, const char* option) {
  if (b.empty) return;
  const double diagonal = b.diagonal();
  if (dt > diagonal)
    throw Error(option, ": ", dt, " is longer than the data's diagonal (", diagonal,
                "): most rays would take no sample and the image would be empty; use at most ",
                diagonal);
}

}  // namespace sm::render
