// Colour interpolation in the spaces ParaView colour maps name, computed as VTK computes them
// (vtkColorTransferFunction, vtkMath: sRGB with the D65 white 0.9505, 1, 1.089).
#pragma once

#include <string>

#include <glm/vec3.hpp>

namespace sm::scene {

// Step: piecewise constant, each interval taking the colour of the point that ends it (VTK's
// VTK_CTF_STEP). Prolab: Konovalenko et al. 2021, a projective transform of CIE XYZ (VTK 9.2's).
enum class ColorSpace { RGB, Lab, HSV, Diverging, Step, Prolab };

// ParaView's names (RGB, Lab, CIELAB, HSV, Diverging, Step, Prolab), case ignored.
// "Lab/CIEDE2000" is taken as Lab, with a warning once per source. Throws FileError naming
// `source` for any other.
ColorSpace parseColorSpace(const std::string& name, const std::string& source);
const char* colorSpaceName(ColorSpace space);

// Colour at fraction f in [0, 1] between a and b (sRGB components in [0, 1]), linearly in the
// space (Step gives b, Diverging is Moreland's Msh interpolation). hsvWrap: take the shorter way
// round the hue circle (VTK's HSVWrap; ParaView's maps leave it off).
glm::dvec3 interpolateColor(const glm::dvec3& a, const glm::dvec3& b, double f, ColorSpace space,
                            bool hsvWrap = false);

// The components of a colour in the space where `space` interpolates it, and back (RGB, Step and
// Diverging: sRGB itself; HSV: hue in [0, 1)). fromSpace clips as VTK does: a colour out of gamut
// is divided by its largest component, negative components become 0.
glm::dvec3 toSpace(const glm::dvec3& rgb, ColorSpace space);
glm::dvec3 fromSpace(const glm::dvec3& c, ColorSpace space);

glm::dvec3 rgbToXyz(const glm::dvec3& rgb);
glm::dvec3 xyzToRgb(const glm::dvec3& xyz);
glm::dvec3 rgbToLab(const glm::dvec3& rgb);
glm::dvec3 labToRgb(const glm::dvec3& lab);
glm::dvec3 xyzToProlab(const glm::dvec3& xyz);
glm::dvec3 prolabToXyz(const glm::dvec3& prolab);
glm::dvec3 rgbToHsv(const glm::dvec3& rgb);
glm::dvec3 hsvToRgb(const glm::dvec3& hsv);

}  // namespace sm::scene
