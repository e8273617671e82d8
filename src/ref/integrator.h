// Integration along one ray through a run of crossings, front to back into an accumulator: the
// Grid samples or the converged integral described in reference_renderer.h. Internal to the
// reference renderer.
#pragma once

#include <span>

#include <glm/vec3.hpp>

#include "ref/reference_renderer.h"

namespace sm::ref {

// Premultiplied colour and opacity composited front to back.
struct Accumulator {
  glm::dvec3 color{0.0};
  double alpha = 0.0;
  // Composites a contribution (premultiplied colour, opacity) behind what is already there.
  void under(const glm::dvec3& c, double a) {
    color += (1.0 - alpha) * c;
    alpha += (1.0 - alpha) * a;
  }
};

class RayIntegrator {
 public:
  // dir must have unit length, so that t is world distance and dt a world spacing.
  RayIntegrator(const ReferenceRenderer& renderer, const glm::dvec3& origin, const glm::dvec3& dir,
                std::span<const float> values, const scene::TransferFunction& tf,
                const RenderSettings& settings);

  // Integrates the crossings (sorted by t_in) into `acc`, stopping early at the threshold.
  void integrate(std::span<const Crossing> crossings, Accumulator& acc, PixelStats& stats) const;

 private:
  struct Medium {
    glm::dvec3 rgb;
    double sigma;
  };
  struct Piece {
    glm::dvec3 color;
    double alpha;
  };
  Medium mediumAt(const Crossing& c, double t, PixelStats& stats) const;
  void grid(std::span<const Crossing> crossings, Accumulator& acc, PixelStats& stats) const;
  void converged(std::span<const Crossing> crossings, Accumulator& acc, PixelStats& stats) const;
  int initialPieces(const Crossing& c, double a, double b, PixelStats& stats) const;
  Piece midpoint(const Crossing& c, double a, double b, PixelStats& stats) const;
  Piece adaptive(const Crossing& c, double a, double b, const Piece& whole, double tol, int depth,
                 PixelStats& stats) const;

  const ReferenceRenderer& renderer_;
  glm::dvec3 origin_, dir_;
  std::span<const float> values_;
  const scene::TransferFunction& tf_;
  const RenderSettings& settings_;
};

}  // namespace sm::ref
