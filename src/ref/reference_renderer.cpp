#include "ref/reference_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "common/check.h"
#include "common/error.h"
#include "common/parallel.h"
#include "ref/integrator.h"
#include "ref/interpolation.h"
#include "ref/ray_element.h"

namespace sm::ref {

using mesh::CellType;

namespace {

// Element boxes are padded by a hair so that rounding in the box and slab computations can never
// drop an element that the exact triangle test would hit.
Box elementBox(const mesh::UnstructuredMesh& m, CellType type, uint32_t index) {
  const uint32_t nv = mesh::numVerts(type);
  const uint32_t* ids = m.cells[mesh::typeIndex(type)].data() + size_t(index) * nv;
  Box b;
  for (uint32_t i = 0; i < nv; ++i) b.extend(m.points[ids[i]]);
  glm::dvec3 magnitude = glm::max(glm::abs(b.lo), glm::abs(b.hi));
  glm::dvec3 pad = 1e-9 * (b.hi - b.lo) + 16.0 * std::numeric_limits<double>::epsilon() * magnitude;
  b.lo -= pad;
  b.hi += pad;
  return b;
}

bool crossingBefore(const Crossing& a, const Crossing& b) {
  if (a.tIn != b.tIn) return a.tIn < b.tIn;
  if (a.tOut != b.tOut) return a.tOut < b.tOut;
  if (a.type != b.type) return a.type < b.type;
  return a.index < b.index;
}

}  // namespace

std::vector<Segment> segments(std::span<const Crossing> crossings, const ElementPredicate& inSet,
                              double relTolerance) {
  std::vector<Segment> out;
  bool open = false;  // the previous crossing belongs to out.back()
  for (uint32_t i = 0; i < crossings.size(); ++i) {
    const Crossing& c = crossings[i];
    if (inSet && !inSet(c.type, c.index)) {
      open = false;
      continue;
    }
    if (open) {
      Segment& s = out.back();
      double slack = relTolerance * std::max(std::abs(s.tOut), std::abs(c.tIn));
      if (c.tIn <= s.tOut + slack) {
        s.tOut = std::max(s.tOut, c.tOut);
        ++s.count;
        continue;
      }
    }
    out.push_back({c.tIn, c.tOut, i, 1});
    open = true;
  }
  return out;
}

ElementPredicate clusterPredicate(const mesh::UnstructuredMesh& mesh,
                                  std::vector<int32_t> clusters) {
  std::sort(clusters.begin(), clusters.end());
  return [&mesh, clusters = std::move(clusters)](CellType type, uint32_t index) {
    const auto& ids = mesh.clusters[mesh::typeIndex(type)];
    int32_t cluster = index < ids.size() ? ids[index] : 0;  // no cluster array: all in cluster 0
    return std::binary_search(clusters.begin(), clusters.end(), cluster);
  };
}

ReferenceRenderer::ReferenceRenderer(const mesh::UnstructuredMesh& mesh) : mesh_(mesh) {
  std::vector<Box> boxes;
  boxes.reserve(mesh.numCells());
  elements_.reserve(mesh.numCells());
  for (CellType type : mesh::kAllCellTypes) {
    const uint64_t n = mesh.numCells(type);
    if (n > gpu::SM_MAX_ELEMS_PER_TYPE)
      throw Error(mesh.source, ": ", n, " ", mesh::cellTypePluralName(type),
                  " exceed the reference renderer's limit of ", gpu::SM_MAX_ELEMS_PER_TYPE);
    for (uint32_t i = 0; i < n; ++i) {
      boxes.push_back(elementBox(mesh, type, i));
      elements_.push_back(gpu::smElemRef(i, mesh::typeIndex(type)));
    }
  }
  bvh_ = Bvh(boxes);
}

std::vector<Crossing> ReferenceRenderer::traceRay(const glm::dvec3& origin,
                                                  const glm::dvec3& dir) const {
  const RayFrame frame(origin, dir);
  std::vector<uint32_t> candidates;
  bvh_.query(origin, dir, candidates);
  std::vector<Crossing> out;
  Interval intervals[kMaxElementIntervals];
  for (uint32_t prim : candidates) {
    const uint32_t ref = elements_[prim];
    const auto type = CellType(gpu::smRefType(ref));
    const uint32_t index = gpu::smRefIndex(ref), nv = mesh::numVerts(type);
    std::span<const uint32_t> ids(mesh_.cells[mesh::typeIndex(type)].data() + size_t(index) * nv,
                                  nv);
    const int n = elementIntervals(frame, type, ids, mesh_.points, intervals);
    for (int i = 0; i < n; ++i) {
      double tIn = std::max(intervals[i].tIn, 0.0);
      if (intervals[i].tOut > tIn) out.push_back({tIn, intervals[i].tOut, type, index});
    }
  }
  std::sort(out.begin(), out.end(), crossingBefore);
  return out;
}

double ReferenceRenderer::scalar(CellType type, uint32_t index, std::span<const float> values,
                                 const glm::dvec3& p) const {
  const uint32_t nv = mesh::numVerts(type);
  const uint32_t* ids = mesh_.cells[mesh::typeIndex(type)].data() + size_t(index) * nv;
  glm::dvec3 corners[kMaxElementVerts];
  double v[kMaxElementVerts];
  for (uint32_t i = 0; i < nv; ++i) {
    corners[i] = mesh_.points[ids[i]];
    v[i] = values[ids[i]];
  }
  return interpolate(type, std::span(corners, nv), std::span(v, nv), p);
}

void ReferenceRenderer::checkInputs(std::span<const float> values,
                                    const RenderSettings& settings) const {
  if (values.size() != mesh_.numPoints())
    throw Error("reference renderer: the field has ", values.size(), " values for ",
                mesh_.numPoints(), " points");
  if (settings.mode == RenderMode::Grid && !(settings.dt > 0.0 && std::isfinite(settings.dt)))
    throw Error("reference renderer: sample spacing dt = ", settings.dt, " is not positive");
  scene::checkClipPlanes(settings.clipPlanes);
  if (!(settings.tolerance > 0.0))
    throw Error("reference renderer: tolerance ", settings.tolerance, " is not positive");
  if (!(settings.earlyTermination > 0.0 && settings.earlyTermination <= 1.0))
    throw Error("reference renderer: early termination threshold ", settings.earlyTermination,
                " is not in (0, 1]");
}

std::vector<Fragment> ReferenceRenderer::fragments(const glm::dvec3& origin, const glm::dvec3& dir,
                                                   std::span<const float> values,
                                                   const scene::TransferFunction& tf,
                                                   const RenderSettings& settings) const {
  checkInputs(values, settings);
  const glm::dvec3 unit = glm::normalize(dir);
  std::vector<Crossing> crossings = traceRay(origin, unit);
  RayIntegrator integrator(*this, origin, unit, values, tf, settings);
  std::vector<Fragment> out;
  PixelStats stats;
  for (const Segment& s : segments(crossings, settings.filter)) {
    Accumulator acc;
    integrator.integrate(std::span(crossings).subspan(s.first, s.count), acc, stats);
    out.push_back({acc.color, acc.alpha, s.tIn});
  }
  return out;
}

void ReferenceRenderer::renderPixel(const glm::dvec3& origin, const glm::dvec3& dir,
                                    std::span<const float> values,
                                    const scene::TransferFunction& tf,
                                    const RenderSettings& settings, glm::vec4& pixel,
                                    PixelStats& stats) const {
  std::vector<Crossing> crossings = traceRay(origin, dir);
  std::vector<Segment> segs = segments(crossings, settings.filter);
  RayIntegrator integrator(*this, origin, dir, values, tf, settings);
  Accumulator acc;
  stats.segments = uint32_t(segs.size());
  for (const Segment& s : segs) {
    stats.crossings += s.count;
    integrator.integrate(std::span(crossings).subspan(s.first, s.count), acc, stats);
  }
  pixel = glm::vec4(glm::vec3(acc.color), float(acc.alpha));
}

RenderResult ReferenceRenderer::render(const scene::Camera& camera, int width, int height,
                                       std::span<const float> values,
                                       const scene::TransferFunction& tf,
                                       const RenderSettings& settings) const {
  checkInputs(values, settings);
  const scene::CameraFrame frame = scene::cameraFrame(camera, width, height);
  RenderResult result{scene::Image(width, height), std::vector<PixelStats>(size_t(width) * height)};
  auto rows = [&](int64_t begin, int64_t end) {
    for (int y = int(begin); y < int(end); ++y)
      for (int x = 0; x < width; ++x)
        renderPixel(frame.pixelOrigin(x, y), frame.pixelDirection(x, y), values, tf, settings,
                    result.image.at(x, y), result.stats[size_t(y) * width + x]);
  };
  parallelFor(height, rows, settings.threads, 1);
  return result;
}

}  // namespace sm::ref
