// The CPU reference renderer: the double-precision test oracle that every GPU image, fragment list
// and shell segment is compared against. It is written independently of the GPU marcher (no
// connectivity, no shells): each ray is intersected brute force with every element whose bounding
// box it touches, found through a BVH over element boxes.
//
// What it computes (docs/ARCHITECTURE.md, "Rendering model", implemented exactly):
//  - Rays: scene::cameraFrame(...).pixelOrigin and pixelDirection (the eye, or with a parallel
//    projection the pixel's point on the plane through it); t is world distance from the origin.
//  - Crossings (traceRay): every interval of the ray (t >= 0) inside an element's triangulated
//    boundary (see ray_element.h for the exact, watertight test), sorted by entry distance. In a
//    conforming mesh consecutive crossings touch exactly (t_out == next t_in, bit for bit).
//  - Segments (segments()): maximal runs of consecutive crossings whose elements satisfy a
//    predicate, joined where they touch: what one rank's shell traversal must find.
//  - Scalars (scalar()): VTK shape functions, tetrahedra barycentric, the others inverted by
//    Newton's method to 1e-10 (interpolation.h); points of the triangulated element outside the
//    isoparametric one are clamped to it.
//  - Grid mode: samples at t_k = k dt, each taken by the first crossing (in entry order) whose
//    [t_in, t_out) holds it, so a sample is never taken twice where non-conforming elements
//    overlap; alpha = 1 - exp(-sigma dt); front-to-back compositing of premultiplied colour.
//  - Converged mode: the continuous emission-absorption integral that Grid mode approaches as
//    dt -> 0: C = int T(t) sigma(t) rgb(t) dt, A = 1 - exp(-int sigma dt). Each crossing is split
//    into one piece per 4 transfer-function table cells its scalar range spans, then each
//    piece is bisected adaptively: a piece's fragment (midpoint sigma and colour, exact
//    exponential attenuation) is compared with the composite of its two halves, and accepted
//    when they differ by at most its share of the tolerance (proportional to its length, summed
//    over the ray to `tolerance`; the midpoint rule's error is O(h^2), a third of that
//    difference). A piece is always bisected at least twice, so every table cell gets a sample
//    and a narrow feature cannot hide between two coincidentally equal estimates; pieces still
//    failing at depth 20 are counted in PixelStats::unconverged. Points covered by overlapping
//    elements count once.
//  - Early termination at `earlyTermination` (default 1.0: off, the oracle's answer).
//  - Clip planes (scene/clip_plane.h): each crossing is cut to the ray's clip span [lo, hi) before
//    integration, so Grid mode keeps the samples with lo <= t_k < hi.
// Precision: all geometry and integration in double; the image stores float. The converged
// error is an estimate, not a bound (on the tests' scenes, tolerance 1e-6 lands within 3e-7 of
// a 1e-9 solution). Degenerate cases: rays through vertices, along edges or in the plane of a
// face are decided as for one infinitesimally shifted ray (symbolic perturbation), so crossings
// neither leak nor double and nothing is NaN; zero-length crossings are dropped; flat elements
// give nothing or rounding-level slivers; inverted elements (faces wound inward) give nothing;
// non-finite scalars are transparent.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/unstructured_mesh.h"
#include "ref/bvh.h"
#include "scene/camera.h"
#include "scene/clip_plane.h"
#include "scene/image.h"
#include "scene/transfer_function.h"

namespace sm::ref {

struct Crossing {
  double tIn = 0.0, tOut = 0.0;
  mesh::CellType type = mesh::CellType::Tet;
  uint32_t index = 0;  // element index within its type
};

struct Segment {
  double tIn = 0.0, tOut = 0.0;
  uint32_t first = 0, count = 0;  // the crossings [first, first + count) of the ray
};

using ElementPredicate = std::function<bool(mesh::CellType type, uint32_t index)>;

// Maximal runs of consecutive crossings whose elements satisfy `inSet` (empty: all), joined when
// one's t_in is within relTolerance * |t| of the previous t_out (or overlaps it).
std::vector<Segment> segments(std::span<const Crossing> crossings, const ElementPredicate& inSet,
                              double relTolerance = 1e-9);

// Elements whose cluster id is one of `clusters` (a rank's clusters). Keeps a reference to mesh.
ElementPredicate clusterPredicate(const mesh::UnstructuredMesh& mesh,
                                  std::vector<int32_t> clusters);

enum class RenderMode { Grid, Converged };

struct RenderSettings {
  double dt = 0.0;  // sample spacing in world units (Grid mode); must be positive
  RenderMode mode = RenderMode::Grid;
  double earlyTermination = 1.0;             // stop once opacity reaches this; 1 = never stop early
  ElementPredicate filter;                   // render only these elements (empty: all)
  std::vector<scene::ClipPlane> clipPlanes;  // draw only what every plane keeps
  double tolerance = 1e-6;                   // Converged mode: target error per pixel channel
  unsigned threads = 0;                      // 0 = all cores
};

// A segment's contribution: premultiplied colour, opacity, and its entry distance.
struct Fragment {
  glm::dvec3 color{0.0};
  double alpha = 0.0;
  double depth = 0.0;
};

struct PixelStats {
  uint32_t crossings = 0;    // crossings of elements that pass the filter
  uint32_t segments = 0;     // segments of those elements
  uint64_t samples = 0;      // scalar evaluations
  uint32_t unconverged = 0;  // Converged mode: pieces that reached the bisection limit
};

struct RenderResult {
  scene::Image image;             // premultiplied RGBA
  std::vector<PixelStats> stats;  // one per pixel, row-major like image.pixels
};

class ReferenceRenderer {
 public:
  // Builds the BVH over element bounds. The mesh is referenced, not copied: keep it alive.
  explicit ReferenceRenderer(const mesh::UnstructuredMesh& mesh);
  explicit ReferenceRenderer(mesh::UnstructuredMesh&&) = delete;  // would dangle

  const mesh::UnstructuredMesh& mesh() const { return mesh_; }

  // Every crossing of the half-line origin + t dir (t >= 0, in units of |dir|), sorted by
  // (t_in, t_out, type, index). A crossing that starts behind the origin starts at 0.
  std::vector<Crossing> traceRay(const glm::dvec3& origin, const glm::dvec3& dir) const;

  // The scalar of `values` (one per mesh point) at point p of element (type, index).
  double scalar(mesh::CellType type, uint32_t index, std::span<const float> values,
                const glm::dvec3& p) const;

  // One fragment per segment of settings.filter along the ray (dir is normalised here), in depth
  // order, each integrated from zero opacity (as a rank does); zero-opacity ones included.
  std::vector<Fragment> fragments(const glm::dvec3& origin, const glm::dvec3& dir,
                                  std::span<const float> values, const scene::TransferFunction& tf,
                                  const RenderSettings& settings) const;

  // The image of the filtered elements (premultiplied RGBA) and per-pixel statistics.
  RenderResult render(const scene::Camera& camera, int width, int height,
                      std::span<const float> values, const scene::TransferFunction& tf,
                      const RenderSettings& settings) const;

 private:
  void checkInputs(std::span<const float> values, const RenderSettings& settings) const;
  void renderPixel(const glm::dvec3& origin, const glm::dvec3& dir, std::span<const float> values,
                   const scene::TransferFunction& tf, const RenderSettings& settings,
                   glm::vec4& pixel, PixelStats& stats) const;

  const mesh::UnstructuredMesh& mesh_;
  std::vector<uint32_t> elements_;  // BVH primitive -> element reference (index << 2 | type)
  Bvh bvh_;
};

}  // namespace sm::ref
