#include "scene/color_space.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>

#include <glm/common.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "common/error.h"
#include "common/log.h"

namespace sm::scene {
namespace {
constexpr double kPi = std::numbers::pi;
// D65 white point, as VTK's vtkMath uses.
constexpr glm::dvec3 kWhite{0.9505, 1.0, 1.089};

double toLinear(double c) {
  return c > 0.04045 ? std::pow((c + 0.055) / 1.055, 2.4) : c / 12.92;
}
double toGamma(double c) {
  return c > 0.0031308 ? 1.055 * std::pow(c, 1.0 / 2.4) - 0.055 : 12.92 * c;
}
double labF(double t) {
  return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116.0;
}
double labFInv(double t) {
  double t3 = t * t * t;
  return t3 > 0.008856 ? t3 : (t - 16.0 / 116.0) / 7.787;
}

// ProLab's projective matrix Q (Konovalenko et al., "ProLab: perceptually uniform projective
// colour coordinate system", IEEE Access 9, 2021), acting on (X/Xn, Y/Yn, Z/Zn, 1) as VTK's
// vtkMath::XYZToProLab applies it. glm is column-major: these are Q's columns.
const glm::dmat4& prolabQ() {
  static const glm::dmat4 q(75.54, 617.72, 48.34, 0.7554,     //
                            486.66, -595.45, 194.94, 3.8666,  //
                            167.39, -22.27, -243.28, 1.6739,  //
                            0.0, 0.0, 0.0, 1.0);
  return q;
}

glm::dvec3 labToMsh(const glm::dvec3& lab) {
  double m = std::sqrt(lab.x * lab.x + lab.y * lab.y + lab.z * lab.z);
  double s = m > 0.001 ? std::acos(std::clamp(lab.x / m, -1.0, 1.0)) : 0.0;
  double h = s > 0.001 ? std::atan2(lab.z, lab.y) : 0.0;
  return {m, s, h};
}

glm::dvec3 mshToLab(const glm::dvec3& msh) {
  return {msh.x * std::cos(msh.y), msh.x * std::sin(msh.y) * std::cos(msh.z),
          msh.x * std::sin(msh.y) * std::sin(msh.z)};
}

// Moreland's hue for an unsaturated end, spun away from the saturated one (VTK's constants).
double adjustHue(const glm::dvec3& msh, double unsatM) {
  if (msh.x >= unsatM - 0.1) return msh.z;
  double spin = msh.y * std::sqrt(unsatM * unsatM - msh.x * msh.x) / (msh.x * std::sin(msh.y));
  return msh.z > -0.3 * kPi ? msh.z + spin : msh.z - spin;
}

double angleDiff(double a, double b) {
  double d = std::abs(a - b);
  while (d >= 2 * kPi) d -= 2 * kPi;
  return d > kPi ? 2 * kPi - d : d;
}

glm::dvec3 interpolateDiverging(const glm::dvec3& a, const glm::dvec3& b, double f) {
  glm::dvec3 m1 = labToMsh(rgbToLab(a)), m2 = labToMsh(rgbToLab(b));
  // Two distinct saturated ends: white goes between them.
  if (m1.y > 0.05 && m2.y > 0.05 && angleDiff(m1.z, m2.z) > 0.33 * kPi) {
    double mid = std::max({m1.x, m2.x, 88.0});
    if (f < 0.5) {
      m2 = {mid, 0, 0};
      f *= 2;
    } else {
      m1 = {mid, 0, 0};
      f = 2 * f - 1;
    }
  }
  if (m1.y < 0.05 && m2.y > 0.05)
    m1.z = adjustHue(m2, m1.x);
  else if (m2.y < 0.05 && m1.y > 0.05)
    m2.z = adjustHue(m1, m2.x);
  return labToRgb(mshToLab(m1 * (1 - f) + m2 * f));
}

}  // namespace

ColorSpace parseColorSpace(const std::string& name, const std::string& source) {
  std::string n = name;
  std::transform(n.begin(), n.end(), n.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (n == "rgb") return ColorSpace::RGB;
  if (n == "lab" || n == "cielab") return ColorSpace::Lab;
  if (n == "lab/ciede2000") {
    // VTK walks a CIEDE2000 shortest path; the straight line in Lab is close, not the same.
    if (log::firstTime("ciede2000 " + source))
      log::warning(source, ": ColorSpace 'Lab/CIEDE2000' is interpolated as Lab");
    return ColorSpace::Lab;
  }
  if (n == "hsv") return ColorSpace::HSV;
  if (n == "diverging") return ColorSpace::Diverging;
  if (n == "step") return ColorSpace::Step;
  if (n == "prolab") return ColorSpace::Prolab;
  throw FileError(source, "unknown ColorSpace '", name,
                  "' (RGB, Lab, HSV, Diverging, Step or Prolab)");
}

const char* colorSpaceName(ColorSpace space) {
  switch (space) {
    case ColorSpace::RGB:
      return "RGB";
    case ColorSpace::Lab:
      return "Lab";
    case ColorSpace::HSV:
      return "HSV";
    case ColorSpace::Diverging:
      return "Diverging";
    case ColorSpace::Step:
      return "Step";
    case ColorSpace::Prolab:
      return "Prolab";
  }
  return "?";
}

glm::dvec3 rgbToXyz(const glm::dvec3& rgb) {
  double r = toLinear(rgb.r), g = toLinear(rgb.g), b = toLinear(rgb.b);
  return {0.4124 * r + 0.3576 * g + 0.1805 * b, 0.2126 * r + 0.7152 * g + 0.0722 * b,
          0.0193 * r + 0.1192 * g + 0.9505 * b};
}

glm::dvec3 xyzToRgb(const glm::dvec3& xyz) {
  const double x = xyz.x, y = xyz.y, z = xyz.z;
  glm::dvec3 c(toGamma(3.2406 * x - 1.5372 * y - 0.4986 * z),
               toGamma(-0.9689 * x + 1.8758 * y + 0.0415 * z),
               toGamma(0.0557 * x - 0.2040 * y + 1.0570 * z));
  // Out of gamut: VTK scales the colour down by its largest component, then clips at 0.
  const double most = std::max({c.r, c.g, c.b});
  if (most > 1.0) c /= most;
  return glm::max(c, glm::dvec3(0.0));
}

glm::dvec3 rgbToLab(const glm::dvec3& rgb) {
  const glm::dvec3 xyz = rgbToXyz(rgb);
  double fx = labF(xyz.x / kWhite.x), fy = labF(xyz.y / kWhite.y), fz = labF(xyz.z / kWhite.z);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

glm::dvec3 labToRgb(const glm::dvec3& lab) {
  double fy = (lab.x + 16.0) / 116.0, fx = fy + lab.y / 500.0, fz = fy - lab.z / 200.0;
  return xyzToRgb(kWhite * glm::dvec3(labFInv(fx), labFInv(fy), labFInv(fz)));
}

glm::dvec3 xyzToProlab(const glm::dvec3& xyz) {
  const glm::dvec4 h = prolabQ() * glm::dvec4(xyz / kWhite, 1.0);
  return glm::dvec3(h) / h.w;
}

glm::dvec3 prolabToXyz(const glm::dvec3& prolab) {
  static const glm::dmat4 inverse = glm::inverse(prolabQ());
  const glm::dvec4 h = inverse * glm::dvec4(prolab, 1.0);
  return glm::dvec3(h) / h.w * kWhite;
}

glm::dvec3 rgbToHsv(const glm::dvec3& c) {
  double mx = std::max({c.r, c.g, c.b}), mn = std::min({c.r, c.g, c.b}), d = mx - mn;
  double s = mx > 0 ? d / mx : 0.0, h = 0.0;
  if (s > 0) {
    if (c.r == mx)
      h = (c.g - c.b) / d / 6.0;
    else if (c.g == mx)
      h = 1.0 / 3.0 + (c.b - c.r) / d / 6.0;
    else
      h = 2.0 / 3.0 + (c.r - c.g) / d / 6.0;
    if (h < 0) h += 1.0;
  }
  return {h, s, mx};
}

// vtkMath::HSVToRGB's sextants (a hue past 1 falls in the red-green one, as there).
glm::dvec3 hsvToRgb(const glm::dvec3& hsv) {
  const double h = hsv.x, s = hsv.y, v = hsv.z, sixth = 1.0 / 6.0;
  glm::dvec3 c;
  if (h > sixth && h <= 2 * sixth)
    c = {(2 * sixth - h) / sixth, 1.0, 0.0};
  else if (h > 2 * sixth && h <= 0.5)
    c = {0.0, 1.0, (h - 2 * sixth) / sixth};
  else if (h > 0.5 && h <= 4 * sixth)
    c = {0.0, (4 * sixth - h) / sixth, 1.0};
  else if (h > 4 * sixth && h <= 5 * sixth)
    c = {(h - 4 * sixth) / sixth, 0.0, 1.0};
  else if (h > 5 * sixth && h <= 1.0)
    c = {1.0, 0.0, (1.0 - h) / sixth};
  else
    c = {1.0, h / sixth, 0.0};
  return (s * c + (1.0 - s)) * v;
}

glm::dvec3 toSpace(const glm::dvec3& rgb, ColorSpace space) {
  switch (space) {
    case ColorSpace::Lab:
      return rgbToLab(rgb);
    case ColorSpace::HSV:
      return rgbToHsv(rgb);
    case ColorSpace::Prolab:
      return xyzToProlab(rgbToXyz(rgb));
    default:
      return rgb;
  }
}

glm::dvec3 fromSpace(const glm::dvec3& c, ColorSpace space) {
  switch (space) {
    case ColorSpace::Lab:
      return labToRgb(c);
    case ColorSpace::HSV:
      return hsvToRgb(c);
    case ColorSpace::Prolab:
      return xyzToRgb(prolabToXyz(c));
    default:
      return c;
  }
}

glm::dvec3 interpolateColor(const glm::dvec3& a, const glm::dvec3& b, double f, ColorSpace space,
                            bool hsvWrap) {
  switch (space) {
    case ColorSpace::RGB:
      return a * (1 - f) + b * f;
    case ColorSpace::Step:
      return b;
    case ColorSpace::Diverging:
      return interpolateDiverging(a, b, f);
    case ColorSpace::HSV: {
      glm::dvec3 h1 = rgbToHsv(a), h2 = rgbToHsv(b);
      if (hsvWrap && std::abs(h1.x - h2.x) > 0.5) (h1.x > h2.x ? h1.x : h2.x) -= 1.0;
      glm::dvec3 h = h1 * (1 - f) + h2 * f;
      if (h.x < 0.0) h.x += 1.0;
      return hsvToRgb(h);
    }
    case ColorSpace::Lab:
    case ColorSpace::Prolab:
      return fromSpace(toSpace(a, space) * (1 - f) + toSpace(b, space) * f, space);
  }
  return a;
}

}  // namespace sm::scene
