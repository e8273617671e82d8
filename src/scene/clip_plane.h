// Clip planes: the volume is drawn only where every plane keeps it, so that a renderer can cut
// into the data to show its inside. Every renderer (GPU, CPU reference) clips the same way: a
// plane keeps the closed half-space its normal points into, dot(x - point, normal) >= 0 (the
// convention of VTK's volume-mapper clipping planes), and along a ray the planes together keep
// one interval of t, samples at t with lo <= t < hi.
#pragma once

#include <span>
#include <string>

#include <glm/vec3.hpp>

namespace sm::scene {

struct ClipPlane {
  glm::dvec3 point{0.0};
  glm::dvec3 normal{0.0, 0.0, 1.0};  // any length but zero: only its direction counts
};

// As many as a box needs; the device keeps them in fixed storage (render_types.h).
constexpr int kMaxClipPlanes = 6;

// Throws SettingError "clip", naming the plane, for more than kMaxClipPlanes planes, a zero or
// non-finite normal or a non-finite point.
void checkClipPlanes(std::span<const ClipPlane> planes);

// The part [lo, hi) of the ray origin + t dir (t in units of |dir|) that every plane keeps;
// lo = -inf and hi = +inf where no plane bounds it, lo >= hi when the ray is clipped away whole.
// A ray parallel to a plane is kept whole or not at all, by its origin's side.
struct ClipSpan {
  double lo, hi;
  bool empty() const { return !(lo < hi); }
};
ClipSpan clipSpan(std::span<const ClipPlane> planes, const glm::dvec3& origin,
                  const glm::dvec3& dir);

}  // namespace sm::scene
