#include "scene/clip_plane.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "common/error.h"
#include "common/setting_error.h"

namespace sm::scene {

namespace {

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

void checkClipPlanes(std::span<const ClipPlane> planes) {
  if (planes.size() > size_t(kMaxClipPlanes))
    throw SettingError("clip", planes.size(), " clip planes, at most ", kMaxClipPlanes);
  for (size_t i = 0; i < planes.size(); ++i) {
    const ClipPlane& p = planes[i];
    if (!finite(p.point) || !finite(p.normal))
      throw SettingError("clip", "clip plane ", i + 1, " has a non-finite point or normal");
    // Squared length in range: a normal of 1e-200 would square to zero and then divide by it.
    const double len = glm::length(p.normal);
    if (!(len > 1e-150 && len < 1e150))
      throw SettingError("clip", "clip plane ", i + 1, " has a zero normal");
  }
}

ClipSpan clipSpan(std::span<const ClipPlane> planes, const glm::dvec3& origin,
                  const glm::dvec3& dir) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  ClipSpan s{-inf, inf};
  for (const ClipPlane& p : planes) {
    const double side = glm::dot(origin - p.point, p.normal);  // >= 0: the origin is kept
    const double rate = glm::dot(dir, p.normal);
    if (rate == 0.0) {
      if (!(side >= 0.0)) return {inf, -inf};
      continue;
    }
    const double t = -side / rate;  // where the ray meets the plane
    if (rate > 0.0)
      s.lo = std::max(s.lo, t);  // the ray goes into the kept side there
    else
      s.hi = std::min(s.hi, t);
  }
  return s;
}

}  // namespace sm::scene
