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
// the range and the outside parts are integrated in closed form with the end values. On a log
// scale the tables' scalar grid is log-spaced (the transfer function's own coordinate), so every
// decade of the range has its share of bins; the scalar still runs linearly along each piece.
//
// On the device every table read is a gather per lane (lavapipe), so the tables are laid out for
// few of them: a colour is three 21-bit fixed-point channels in one 64-bit word (one gather, not
// three or four; the step, 2^-21, is far below the interpolation error), and the cumulative
// extinction is stored as pairs (S[i], S[i+1]) (one gather per lookup, not two). The CPU works
// with the same quantised colours, so it computes what the device does.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "scene/transfer_function.h"

namespace sm::render {

struct PreintegrationTable {
  // Device layout, one buffer of 64-bit words: colors (encodeColor), then the cumulative
  // extinction as pairs (S[i], S[i+1]) for i < cumulative.size() - 1, then the two ends as vec4s
  // (rgb, sigma): below lo, above hi.
  std::vector<uint64_t> deviceWords() const;
  size_t deviceColorBytes() const { return colors.size() * sizeof(uint64_t); }

  // 21 bits per channel over [0, 1] (clamped); decodeColor(encodeColor(c)) is what both the
  // device and integrate() use.
  static constexpr int kColorBits = 21;
  static uint64_t encodeColor(glm::vec3 c);
  static glm::vec3 decodeColor(uint64_t w);

  int scalarBins = 0;  // of the colour table along sf and sb, over [lo, hi]
  int lengthBins = 0;  // along sqrt(tau / tauMax)
  double lo = 0, hi = 1;
  scene::ScalarScale scale = scene::ScalarScale::Linear;  // of the scalar grid over [lo, hi]
  double sigmaMax = 0, tauMax = 0;
  std::vector<float> cumulative;       // S at cumulativeBins points over [lo, hi] (per scalar unit)
  std::vector<glm::vec3> colors;       // N (quantised) at [(l * bins + b) * bins + f]
  std::vector<float> sigma;            // extinction per transfer-function entry over [lo, hi]
  glm::vec4 below{0.0f}, above{0.0f};  // the function's rgb and extinction below lo and above hi

  // Below this change of the tables' coordinate (the scalar's change relative to the range; on a
  // log scale, relative to the larger end and to ln(hi / lo)) the mean extinction is taken at the
  // midpoint: the difference of S would cancel in single precision on the device. The same
  // coordinate change on both scales: relative to the larger end alone, a log scale's threshold
  // was ln(hi / lo) times finer, and pieces just above it lost so many digits to the cancellation
  // that images on 1 and 3 ranks differed by 1.9e-5 (now 2.6e-6; app.log_scale).
  static constexpr double kSmallDelta = 1e-3;

  // Where s falls on the tables' scalar grid, in [0, 1] (s clamped to [lo, hi]).
  double coordinate(double s) const;
  // The scalar at point i of an n-point grid over [lo, hi] (i = 0: lo, i = n - 1: hi).
  double gridValue(int i, int n) const;

  // Colour (premultiplied) and opacity of a linear piece, on the CPU exactly as the shader does it.
  glm::dvec4 integrate(double sf, double sb, double L) const;

 private:
  double cumulativeAt(double s) const;  // S(s), s clamped to [lo, hi]
  double sigmaAt(double s) const;       // the transfer function's extinction at s
  glm::dvec3 colorAt(double sf, double sb, double L) const;
  glm::dvec4 integrateInside(double sf, double sb, double L) const;
  static glm::dvec4 integrateConstant(glm::vec4 end, double L);
};

// The device buffer's bytes of buildPreintegration(tf) with these bins (deviceWords): what an
// element-exact frame allocates beside the scene, for the out-of-memory advice.
uint64_t preintegrationDeviceBytes(const scene::TransferFunction& tf, int scalarBins = 128,
                                   int lengthBins = 32);

PreintegrationTable buildPreintegration(const scene::TransferFunction& tf, int scalarBins = 128,
                                        int lengthBins = 32, double tauMax = 16.0,
                                        int quadrature = 128);

}  // namespace sm::render
