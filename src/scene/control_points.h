// Control points of ParaView's colour and opacity maps, evaluated exactly as VTK evaluates them
// (vtkColorTransferFunction::GetTable, vtkPiecewiseFunction::GetTable).
//
// Between two points the left point's midpoint and sharpness shape the curve. The midpoint is
// where, as a fraction of the interval, the value is half way (0.5: the centre); sharpness 0 is
// linear in the remapped fraction, 1 a step at the midpoint, and in between the fraction is bent
// towards the ends (exponent 1 + 10 sharpness) and run through a Hermite curve whose end slopes
// shrink as (1 - sharpness). The midpoint is kept within [1e-5, 1 - 1e-5].
#pragma once

#include <span>

#include <glm/vec3.hpp>

#include "scene/color_space.h"

namespace sm::scene {

struct OpacityNode {
  double x, y, midpoint = 0.5, sharpness = 0.0;
};

struct ColorNode {
  double x;
  glm::dvec3 rgb;
  double midpoint = 0.5, sharpness = 0.0;
};

// Nodes sorted by x (equal x allowed: a jump, the first of them taking x itself). Below the first
// node its value, above the last the last's (VTK's clamping). No nodes: 0.
double evaluateOpacity(std::span<const OpacityNode> nodes, double x);
glm::dvec3 evaluateColor(std::span<const ColorNode> nodes, double x, ColorSpace space,
                         bool hsvWrap = false);

// The interval fraction s in [0, 1] remapped by a midpoint (s = midpoint gives 0.5).
double applyMidpoint(double s, double midpoint);

}  // namespace sm::scene
