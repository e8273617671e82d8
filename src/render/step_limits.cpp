#include "render/step_limits.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "common/setting_error.h"

namespace sm::render {

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

void checkStep(double dt, const glm::dvec3& eye, const mesh::Bounds& b) {
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw SettingError("step", "the sample distance must be positive and finite, not ", dt);
  const double finest = finestStep(eye, b);
  if (dt < finest)
    throw SettingError(
        "step", dt, " is finer than float distances along a ray resolve in this view ",
        "(the data reaches ", finest * 0x1p24, " from the eye); use at least ", finest);
}

void checkStepNotBeyondData(double dt, const mesh::Bounds& b) {
  if (b.empty) return;
  const double diagonal = b.diagonal();
  if (dt > diagonal)
    throw SettingError(
        "step", dt, " is longer than the data's diagonal (", diagonal,
        "): most rays would take no sample and the image would be empty; use at most ", diagonal);
}

}  // namespace sm::render
