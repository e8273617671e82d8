// Pre-integrated transfer function for element-exact integration (beyond the paper's fixed-step
// sampling): what a ray accumulates over a piece of length L along which the scalar runs linearly
// from sf to sb.
//
//   opacity  alpha = 1 - exp(-L * mean sigma),  mean sigma = (S(sb) - S(sf)) / (sb - sf)
//            with S the cumulative extinction over the scalar (a 1D table): exact in L;
//   colour   C = alpha * N(sf, sb, L), N the extinction- and attenuation-weighted mean colour,
//            tabulated over (sf, sb, sqrt(L sigmaMax / tauMax)) and interpolated trilinearly. N is
//            smooth in all three, which keeps interpolation error small.
// Outside [lo, hi] the transfer function is constant, so a piece is split where its scalar leaves
// the range and the outside parts are integrated with the end values.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "scene/transfer_function.h"

namespace sm::render {

struct PreintegrationTable {
  // Device layout: colors (vec4) then cumulative (float) in one buffer.
  size_t deviceBytes() const {
    return colors.size() * sizeof(glm::vec4) + cumulative.size() * sizeof(float);
  }
  int scalarBins = 0;  // of the colour table along sf and sb, over [lo, hi]
  int lengthBins = 0;  // along sqrt(tau / tauMax)
  double lo = 0, hi = 1;
  double sigmaMax = 0, tauMax = 0;
  std::vector<float> cumulative;  // S at cumulativeBins points over [lo, hi] (per scalar unit)
  std::vector<glm::vec4> colors;  // N: rgb (a unused) at [(l * bins + b) * bins + f]
  std::vector<float> sigma;       // extinction per transfer-function entry over [lo, hi]

  // Below this scalar change (relative to the range) the mean extinction is taken at the midpoint:
  // the difference of S would cancel in single precision on the device.
  static constexpr double kSmallDelta = 1e-3;

  // Colour (premultiplied) and opacity of a linear piece, on the CPU exactly as the shader does it.
  glm::dvec4 integrate(double sf, double sb, double L) const;

 private:
  double cumulativeAt(double s) const;  // S(s), s clamped to [lo, hi]
  double sigmaAt(double s) const;       // the transfer function's extinction at s
  glm::dvec3 colorAt(double sf, double sb, double L) const;
  glm::dvec4 integrateInside(double sf, double sb, double L) const;
};

PreintegrationTable buildPreintegration(const scene::TransferFunction& tf, int scalarBins = 128,
                                        int lengthBins = 32, double tauMax = 16.0,
                                        int quadrature = 128);

}  // namespace sm::render
