// Colour interpolation in the spaces ParaView colour maps name.
#pragma once

#include <string>

#include <glm/vec3.hpp>

namespace sm::scene {

enum class ColorSpace { RGB, Lab, HSV, Diverging };
ColorSpace parseColorSpace(const std::string& name, const std::string& source);

// Colour at fraction f in [0, 1] between a and b (sRGB components in [0, 1]). Diverging is
// Moreland's Msh interpolation, as ParaView's "Cool to Warm" uses.
glm::dvec3 interpolateColor(const glm::dvec3& a, const glm::dvec3& b, double f, ColorSpace space);

glm::dvec3 rgbToLab(const glm::dvec3& rgb);
glm::dvec3 labToRgb(const glm::dvec3& lab);

}  // namespace sm::scene
