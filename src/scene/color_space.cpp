#include "scene/color_space.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/common.hpp>

#include "common/error.h"

namespace sm::scene {
namespace {
constexpr double kPi = std::numbers::pi;
// D65 white point, as VTK's vtkMath uses.
constexpr double kXn = 0.9505, kYn = 1.0, kZn = 1.089;

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

double adjustHue(const glm::dvec3& msh, double unsatM) {
  if (msh.x >= unsatM - 0.1) return msh.z;
  double spin = msh.y * std::sqrt(unsatM * unsatM - msh.x * msh.x) / (msh.x * std::sin(msh.y));
  return msh.z > -kPi / 3 ? msh.z + spin : msh.z - spin;
}

glm::dvec3 rgbToHsv(const glm::dvec3& c) {
  double mx = std::max({c.r, c.g, c.b}), mn = std::min({c.r, c.g, c.b}), d = mx - mn;
  double h = 0.0;
  if (d > 0) {
    if (mx == c.r)
      h = std::fmod((c.g - c.b) / d + 6.0, 6.0);
    else if (mx == c.g)
      h = (c.b - c.r) / d + 2.0;
    else
      h = (c.r - c.g) / d + 4.0;
    h /= 6.0;
  }
  return {h, mx > 0 ? d / mx : 0.0, mx};
}

glm::dvec3 hsvToRgb(const glm::dvec3& hsv) {
  double h = std::fmod(hsv.x, 1.0) * 6.0, s = hsv.y, v = hsv.z;
  int i = int(std::floor(h)) % 6;
  double f = h - std::floor(h), p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  switch (i) {
    case 0:
      return {v, t, p};
    case 1:
      return {q, v, p};
    case 2:
      return {p, v, t};
    case 3:
      return {p, q, v};
    case 4:
      return {t, p, v};
    default:
      return {v, p, q};
  }
}

}  // namespace

ColorSpace parseColorSpace(const std::string& name, const std::string& source) {
  if (name == "RGB") return ColorSpace::RGB;
  if (name == "Lab" || name == "CIELAB" || name == "Lab/CIEDE2000") return ColorSpace::Lab;
  if (name == "HSV") return ColorSpace::HSV;
  if (name == "Diverging") return ColorSpace::Diverging;
  throw FileError(source, "unknown ColorSpace '", name, "' (RGB, Lab, HSV or Diverging)");
}

glm::dvec3 rgbToLab(const glm::dvec3& rgb) {
  double r = toLinear(rgb.r), g = toLinear(rgb.g), b = toLinear(rgb.b);
  double x = 0.4124 * r + 0.3576 * g + 0.1805 * b;
  double y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
  double z = 0.0193 * r + 0.1192 * g + 0.9505 * b;
  double fx = labF(x / kXn), fy = labF(y / kYn), fz = labF(z / kZn);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

glm::dvec3 labToRgb(const glm::dvec3& lab) {
  double fy = (lab.x + 16.0) / 116.0, fx = fy + lab.y / 500.0, fz = fy - lab.z / 200.0;
  double x = kXn * labFInv(fx), y = kYn * labFInv(fy), z = kZn * labFInv(fz);
  double r = 3.2406 * x - 1.5372 * y - 0.4986 * z;
  double g = -0.9689 * x + 1.8758 * y + 0.0415 * z;
  double b = 0.0557 * x - 0.2040 * y + 1.0570 * z;
  return glm::clamp(glm::dvec3(toGamma(r), toGamma(g), toGamma(b)), 0.0, 1.0);
}

glm::dvec3 interpolateColor(const glm::dvec3& a, const glm::dvec3& b, double f, ColorSpace space) {
  switch (space) {
    case ColorSpace::RGB:
      return a * (1 - f) + b * f;
    case ColorSpace::Lab:
      return labToRgb(rgbToLab(a) * (1 - f) + rgbToLab(b) * f);
    case ColorSpace::HSV:
      return hsvToRgb(rgbToHsv(a) * (1 - f) + rgbToHsv(b) * f);
    case ColorSpace::Diverging: {
      glm::dvec3 m1 = labToMsh(rgbToLab(a)), m2 = labToMsh(rgbToLab(b));
      if (m1.y > 0.05 && m2.y > 0.05 && std::abs(m1.z - m2.z) > kPi / 3) {
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
  }
  return a;
}

}  // namespace sm::scene
