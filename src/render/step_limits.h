// What sample step a frame can honour: the renderer checks every frame's step here, and the
// front ends check a step once for the whole data set before any rank renders (an agreed error).
#pragma once

#include <glm/vec3.hpp>

#include "mesh/bounds.h"

namespace sm::render {

// Samples sit at t = k dt, computed in float: past 2^24 steps from the eye, consecutive sample
// positions are no longer distinct (and past 2^32 the device's step index would wrap), so a step
// finer than the farthest corner of `b` over 2^24 cannot be honoured. 0 for empty bounds.
double finestStep(const glm::dvec3& eye, const mesh::Bounds& b);

// Throws SettingError "step" unless `dt` is finite, positive and at least finestStep(eye, b).
void checkStep(double dt, const glm::dvec3& eye, const mesh::Bounds& b);

// Throws SettingError "step" when sampling at `dt` would leave most rays without a sample: a step
// longer than the diagonal of bounds b (the image would be empty, or a few scattered pixels).
void checkStepNotBeyondData(double dt, const mesh::Bounds& b);

}  // namespace sm::render
