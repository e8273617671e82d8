#include "ray_harness.h"

#include <cmath>
#include <random>
#include <sstream>

#include <glm/geometric.hpp>

#include "common/check.h"
#include "prep/prepare.h"
#include "prep/vertex_order.h"
#include "ref/reference_renderer.h"
#include "render_harness.h"
#include "vk/context.h"

namespace sm::test {
namespace {

render::WorldRay ray(const glm::dvec3& o, const glm::dvec3& d) {
  return {o, glm::normalize(d)};
}

}  // namespace

std::vector<render::WorldRay> hardRays(const mesh::UnstructuredMesh& m, int random, int gridCells,
                                       uint32_t seed) {
  std::vector<render::WorldRay> rays;
  mesh::Bounds b = m.bounds();
  glm::dvec3 c = b.center(), e = b.extent();
  double far = 2.0 * b.diagonal();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1), s(-1, 1);
  for (int i = 0; i < random; ++i) {
    glm::dvec3 dir = glm::normalize(glm::dvec3(s(rng), s(rng), s(rng)));
    glm::dvec3 target = b.lo + glm::dvec3(u(rng), u(rng), u(rng)) * e;
    rays.push_back(ray(target - dir * far, dir));
  }
  // Axis-aligned rays through the grid's vertex columns, edge midlines and cell centres, both ways.
  for (int axis = 0; axis < 3; ++axis) {
    int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    for (int i = 0; i <= 2 * gridCells; ++i) {
      for (int j = 0; j <= 2 * gridCells; ++j) {
        glm::dvec3 o = c;
        o[a1] = b.lo[a1] + e[a1] * i / (2.0 * gridCells);
        o[a2] = b.lo[a2] + e[a2] * j / (2.0 * gridCells);
        for (double sign : {-1.0, 1.0}) {
          glm::dvec3 d(0.0);
          d[axis] = sign;
          glm::dvec3 start = o;
          start[axis] = c[axis] - sign * far;
          rays.push_back({start, d});
        }
      }
    }
  }
  // Rays aimed exactly at mesh vertices, edge midpoints and face centres from random directions.
  auto aim = [&](const glm::dvec3& target) {
    glm::dvec3 dir = glm::normalize(glm::dvec3(s(rng), s(rng), s(rng)));
    rays.push_back(ray(target - dir * far, dir));
  };
  const auto& cells = m.cells[mesh::typeIndex(mesh::CellType::Tet)];
  for (size_t v = 0; v < m.points.size(); v += std::max<size_t>(1, m.points.size() / 1500))
    aim(m.points[v]);
  for (mesh::CellType t : mesh::kAllCellTypes) {
    const auto& conn = m.cells[mesh::typeIndex(t)];
    const uint32_t nv = mesh::numVerts(t);
    size_t stride = std::max<size_t>(1, conn.size() / nv / 500) * nv;
    for (size_t e = 0; e + nv <= conn.size(); e += stride) {
      aim((m.points[conn[e]] + m.points[conn[e + 1]]) * 0.5);
      glm::dvec3 f(0.0);
      for (uint32_t k = 0; k < 3; ++k) f += m.points[conn[e + mesh::faceVert(t, 0, k)]];
      aim(f / 3.0);
    }
  }
  (void)cells;
  return rays;
}

RayComparison compareRays(const mesh::UnstructuredMesh& original,
                          const std::vector<float>& inputValues,
                          const render::RenderSettings& settings,
                          const std::vector<render::WorldRay>& worldRays) {
  // The reference's samples (Grid mode) are sampled integration's: the test asks for that.
  SM_CHECK_MSG(settings.integration == render::Integration::Sampled,
               "compareRays: the grid reference is sampled integration's");
  // Compare on the geometry the GPU actually sees: positions and rays as float offsets from the
  // rebasing origin (directions as float). Otherwise a ray that lies exactly in a face plane in
  // float lies just inside or outside it in double, and the two renderers get different rays.
  const glm::dvec3 origin = prep::makeGlobalFrame(original.bounds()).origin;
  auto snap = [&](const glm::dvec3& p) { return origin + glm::dvec3(glm::vec3(p - origin)); };
  mesh::UnstructuredMesh snapped = original;
  for (auto& p : snapped.points) p = snap(p);
  // The reference sees the GPU's vertex order, so that both split warped quads alike.
  std::vector<uint32_t> order =
      prep::globalVertexOrder(snapped.points, prep::makeGlobalFrame(original.bounds()));
  mesh::UnstructuredMesh input = inGlobalVertexOrder(snapped);
  std::vector<float> values(inputValues.size());
  for (size_t i = 0; i < order.size(); ++i) values[i] = inputValues[order[i]];
  std::vector<render::WorldRay> rays(worldRays);
  for (auto& r : rays) {
    r.origin = snap(r.origin);
    r.direction = glm::dvec3(glm::vec3(r.direction));
  }
  mesh::UnstructuredMesh m = input;
  auto prepared =
      prep::prepareRank(m, prep::makeGlobalFrame(original.bounds()), prep::PrepOptions{}).rank;
  vk::Context ctx;
  render::GpuScene scene(ctx, prepared, std::move(prepared.positions));
  scene.setScalars(prep::gatherScalars(prepared, values));
  comp::DeepCompositor compositor(ctx, nullptr, int(rays.size()), 1, comp::CompositorOptions{});
  render::Renderer renderer(ctx, scene, compositor);
  render::FrameResult frame = renderer.renderRays(settings, rays);
  auto lists = renderer.lastFragments();
  expectOtherTracerAgrees(ctx, scene, compositor, settings, renderer, frame, &rays);

  ref::ReferenceRenderer reference(input);
  ref::RenderSettings rs;
  rs.dt = settings.dt;
  rs.earlyTermination = std::min(settings.earlyTermination, 1.0);
  RayComparison cmp;
  cmp.rays = rays.size();
  cmp.lost = frame.counters.lostRays;
  cmp.stepLimit = frame.counters.stepLimitHits;
  const double significant = 1e-3;
  // The largest opacity one sample can add: explains a ray that differs by a boundary tie.
  double maxSigma = 0;
  for (const auto& e : settings.transferFunction.table)
    maxSigma = std::max(maxSigma, double(e.a) * settings.transferFunction.opacityScale /
                                      settings.transferFunction.unitDistance);
  const double oneSample = 1.0 - std::exp(-maxSigma * settings.dt);
  for (size_t i = 0; i < rays.size(); ++i) {
    glm::dvec3 o = rays[i].origin, d = rays[i].direction;
    auto want = reference.fragments(o, d, values, settings.transferFunction, rs);
    glm::dvec4 refColor(0.0), gpuColor(0.0);
    int refSignificant = 0, gpuSignificant = 0;
    double refDepth = -1, gpuDepth = -1;
    for (const auto& f : want) {
      refColor += (1.0 - refColor.a) * glm::dvec4(f.color, f.alpha);
      if (f.alpha > significant && refSignificant++ == 0) refDepth = f.depth;
    }
    for (const auto& f : lists[i]) {
      gpuColor += (1.0 - gpuColor.a) * glm::dvec4(f.color);
      if (f.color.a > significant && gpuSignificant++ == 0) gpuDepth = f.depth;
    }
    bool nan = false;
    double rayErr = 0;
    for (int c = 0; c < 4; ++c) rayErr = std::max(rayErr, std::abs(gpuColor[c] - refColor[c]));
    cmp.rayErrors.push_back(rayErr);
    bool tie = rayErr > 2e-4 && rayErr <= oneSample + 2e-4 && refSignificant == gpuSignificant;
    cmp.sampleTies += tie;
    for (int c = 0; c < 4 && !tie; ++c) {
      nan = nan || !std::isfinite(gpuColor[c]);
      double err = std::abs(gpuColor[c] - refColor[c]);
      if (err > cmp.maxColorError) {
        cmp.maxColorError = err;
        cmp.worstRay = i;
        std::ostringstream os;
        os << "ray " << i << " origin (" << o.x << ", " << o.y << ", " << o.z << ") dir (" << d.x
           << ", " << d.y << ", " << d.z << "): reference";
        for (const auto& f : want) os << " [t " << f.depth << " a " << f.alpha << "]";
        os << "; GPU";
        for (const auto& f : lists[i]) os << " [t " << f.depth << " a " << f.color.a << "]";
        cmp.worst = os.str();
      }
    }
    cmp.nanRays += nan;
    if (refSignificant != gpuSignificant)
      ++cmp.segmentCountMismatches;
    else if (refDepth >= 0)
      cmp.maxDepthError = std::max(cmp.maxDepthError, std::abs(refDepth - gpuDepth));
  }
  return cmp;
}

}  // namespace sm::test
