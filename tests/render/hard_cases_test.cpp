// docs/DESIGN.md's hard cases, one test each, with their tolerances stated. Every case requires
// zero lost rays, no step-limit hit, no NaN, and agreement with the double-precision CPU reference
// ray by ray: composited RGBA within 2e-4 (float against double over a whole ray) and the first
// significant fragment's depth within 1e-4 of the scene size.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

#include <glm/geometric.hpp>

#include "common/error.h"
#include "mesh/mesh_builder.h"
#include "prep/prepare.h"
#include "ray_harness.h"
#include "render/gpu_scene.h"
#include "render/step_limits.h"
#include "render_harness.h"
#include "scene/view_defaults.h"
#include "support/test_meshes.h"
#include "test_meshes.h"

namespace sm::render {
namespace {

using ref::test::Split;

// Sampled: the rays are compared with the reference's samples on the same grid, and some tests
// count samples (the element-exact test asks for its integration).
RenderSettings hardSettings(double lo, double hi, double size) {
  RenderSettings s;
  s.integration = Integration::Sampled;
  s.transferFunction = scene::makeTransferFunction("cool-to-warm");
  s.transferFunction.lo = lo;
  s.transferFunction.hi = hi;
  s.transferFunction.unitDistance = 0.5 * size;
  s.dt = 0.0123 * size;
  s.earlyTermination = 2.0;
  return s;
}

// The unit cube seen at an angle from outside, size x size pixels.
RenderSettings cubeView(int size) {
  RenderSettings s = hardSettings(0, 2, 1);
  s.width = s.height = size;
  s.camera.eye = {2.0, -1.5, 1.2};
  s.camera.at = {0.5, 0.5, 0.5};
  return s;
}

struct RayTolerance {
  double color = 2e-4;            // composited RGBA per ray
  double tieFraction = 1e-3;      // rays allowed to differ by one boundary sample
  double mismatchFraction = 0.0;  // rays allowed a different count of significant fragments
  bool checkSegments = true;      // compare fragment counts and first depths at all
};

// checkSegments = false: unwelded touching pieces on one rank: the GPU ends a segment at each
// shell, the reference merges touching runs of elements; the colour must agree either way.
void expectRaysMatch(const std::string& name, const mesh::UnstructuredMesh& m,
                     const std::vector<float>& f, const RenderSettings& s, int gridCells,
                     size_t minRays = 10000, RayTolerance tol = {}) {
  const bool checkSegments = tol.checkSegments;
  auto rays = test::hardRays(m, 10000, gridCells, 11);
  ASSERT_GE(rays.size(), minRays) << name;
  auto c = test::compareRays(m, f, s, rays);
  const double size = m.bounds().diagonal();
  std::printf(
      "[rays] %-28s %6llu rays: max colour error %.2g, max depth error %.2g, count mismatches "
      "%llu, "
      "sample ties %llu\n",
      name.c_str(), (unsigned long long)c.rays, c.maxColorError, c.maxDepthError,
      (unsigned long long)c.segmentCountMismatches, (unsigned long long)c.sampleTies);
  EXPECT_LE(double(c.sampleTies), tol.tieFraction * double(c.rays)) << name;
  EXPECT_EQ(c.lost, 0u) << name;
  EXPECT_EQ(c.stepLimit, 0u) << name;
  EXPECT_EQ(c.nanRays, 0u) << name;
  EXPECT_LT(c.maxColorError, tol.color) << name << ": worst " << c.worst;
  if (checkSegments) {
    EXPECT_LT(c.maxDepthError, 1e-4 * size) << name;
    EXPECT_LE(double(c.segmentCountMismatches), tol.mismatchFraction * double(c.rays)) << name;
  }
}

std::vector<float> smoothField(const mesh::UnstructuredMesh& m, glm::dvec3 lo, double size) {
  return ref::test::pointField(m, [&](const glm::dvec3& p) {
    glm::dvec3 q = (p - lo) / size;
    return std::sin(3 * q.x) + q.y * q.z + 0.5 * q.z;
  });
}

// Rays through vertices and along edges: axis-aligned rays on a power-of-two grid hit vertex
// columns and edges exactly in float.
TEST(HardCases, RaysThroughVerticesAndAlongEdges) {
  for (Split split : ref::test::kAllSplits) {
    auto m = ref::test::cubeMesh(split, 4);
    expectRaysMatch("vertices_edges_" + ref::test::splitName(split), m,
                    smoothField(m, {0, 0, 0}, 1), hardSettings(0, 2, 1), 4);
  }
}

// Rays grazing faces: lying exactly in the outer boundary planes and in interior face planes with
// oblique in-plane directions (not the grid's axes), and rays meeting the boundary at a tilt of
// 1e-6 to 1e-3 rad. In-plane rays are decided by the exact predicates: colour within 1e-3 of the
// reference. A tilted ray's entry point is ill-conditioned in float: rounding of the projected
// vertices (~1e-7 of the scene) moves it by ~1e-7 / tilt along the ray, so its colour may differ by
// up to sigma_max * 3e-7 / tilt (measured: a third of that at worst). No lost ray, no NaN, either
// way.
struct GrazingRays {
  std::vector<WorldRay> rays;
  std::vector<double> tilt;  // 0: in the plane
};

GrazingRays grazingRays(int perPlane, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0), angle(0.0, 6.283185307179586);
  GrazingRays g;
  for (double plane : {0.0, 0.25, 0.5, 1.0}) {
    for (int axis = 0; axis < 3; ++axis) {
      for (int i = 0; i < perPlane; ++i) {
        double a = angle(rng), tilt = 0;
        glm::dvec3 d(0.0), o(0.5);
        d[(axis + 1) % 3] = std::cos(a);
        d[(axis + 2) % 3] = std::sin(a);
        o[(axis + 1) % 3] = u(rng);
        o[(axis + 2) % 3] = u(rng);
        o[axis] = plane;
        if (i % 4 == 3 && (plane == 0.0 || plane == 1.0)) {  // just touching the boundary
          tilt = std::pow(10.0, -3.0 - 3.0 * u(rng));
          d[axis] = plane == 0.0 ? tilt : -tilt;
          d = glm::normalize(d);
        }
        g.rays.push_back({o - 3.0 * d, d});
        g.tilt.push_back(tilt);
      }
    }
  }
  return g;
}

TEST(HardCases, RaysGrazingFaces) {
  const RenderSettings s = hardSettings(0, 2, 1);
  double sigmaMax = 0;
  for (const auto& e : s.transferFunction.table)
    sigmaMax = std::max(sigmaMax, double(e.a) / s.transferFunction.unitDistance);
  for (Split split : {Split::Tets5, Split::Hex, Split::Pyramids}) {
    auto m = ref::test::cubeMesh(split, 4);
    GrazingRays g = grazingRays(900, 17);
    ASSERT_GE(g.rays.size(), 10000u);
    auto c = test::compareRays(m, smoothField(m, {0, 0, 0}, 1), s, g.rays);
    EXPECT_EQ(c.lost, 0u);
    EXPECT_EQ(c.stepLimit, 0u);
    EXPECT_EQ(c.nanRays, 0u);
    double inPlane = 0, tiltedRatio = 0;  // worst error; worst error over its bound
    for (size_t i = 0; i < g.rays.size(); ++i) {
      if (g.tilt[i] == 0) {
        inPlane = std::max(inPlane, c.rayErrors[i]);
        EXPECT_LT(c.rayErrors[i], 1e-3) << "in-plane ray " << i;
      } else {
        double bound = 1e-3 + sigmaMax * 3e-7 / g.tilt[i];
        tiltedRatio = std::max(tiltedRatio, c.rayErrors[i] / bound);
        EXPECT_LT(c.rayErrors[i], bound) << "ray " << i << " tilt " << g.tilt[i];
      }
    }
    std::printf(
        "[rays] grazing_%-20s %6llu rays: in-plane max colour error %.2g; tilted: worst "
        "error / bound %.2g\n",
        ref::test::splitName(split).c_str(), (unsigned long long)c.rays, inPlane, tiltedRatio);
  }
}

TEST(HardCases, FarFromTheOriginWithSmallElements) {
  const glm::dvec3 lo(1e6, -2e6, 3e6);
  const double size = 0.01;
  auto m = ref::test::cubeMesh(Split::Tets5, 4, size, lo);
  expectRaysMatch("far_from_origin", m, smoothField(m, lo, size), hardSettings(0, 2, size), 4);
}

// Slivers: the cube squashed to 1/1000 of its height makes every tetrahedron nearly flat. Float
// coordinates resolve such an element's thickness only to ~1e-4 of itself, so rays that run along
// a boundary plane through them (grazing, nearly transparent here) may take a few samples more or
// less than the double-precision reference: per-ray colour within 1e-3, at most 0.5% of rays off by
// one boundary sample, at most 0.1% with a different count of significant fragments. Still no lost
// ray, no step-limit hit, no NaN.
TEST(HardCases, SliversAndNearDegenerateElements) {
  auto m = ref::test::cubeMesh(Split::Tets5, 4);
  for (auto& p : m.points) p.z *= 1e-3;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> j(-0.02, 0.02);
  for (auto& p : m.points)
    if (p.x > 0 && p.x < 1 && p.y > 0 && p.y < 1) p += glm::dvec3(j(rng), j(rng), 0);
  auto s = hardSettings(0, 2, 1);
  s.dt = 1e-4;
  RayTolerance tol;
  tol.color = 1e-3;
  tol.tieFraction = 5e-3;
  tol.mismatchFraction = 1e-3;
  expectRaysMatch("slivers", m, smoothField(m, {0, 0, 0}, 1), s, 4, 10000, tol);
}

TEST(HardCases, WarpedQuadFaces) {
  for (Split split : {Split::Hex, Split::Wedges, Split::Pyramids}) {
    auto m = ref::test::cubeMesh(split, 4);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> j(-0.05, 0.05);
    for (auto& p : m.points)
      if (p.x > 0 && p.x < 1 && p.y > 0 && p.y < 1 && p.z > 0 && p.z < 1)
        p += glm::dvec3(j(rng), j(rng), j(rng));
    expectRaysMatch("warped_" + ref::test::splitName(split), m, smoothField(m, {0, 0, 0}, 1),
                    hardSettings(0, 2, 1), 4);
  }
}

// Inverted elements in the input are reoriented at load: the image equals the clean mesh's.
TEST(HardCases, InvertedElementsInTheInput) {
  auto clean = ref::test::cubeMesh(Split::Hex, 3);
  mesh::MeshBuilder b("inverted.vtu");
  b.setPoints(clean.points);
  const auto& hexes = clean.cells[mesh::typeIndex(mesh::CellType::Hex)];
  for (size_t e = 0; e < hexes.size() / 8; ++e) {
    int64_t v[8];
    for (int i = 0; i < 8; ++i) v[i] = hexes[8 * e + i];
    if (e % 2) {  // mirror every other hexahedron: what meshio-converted files carry
      std::swap(v[1], v[3]);
      std::swap(v[5], v[7]);
    }
    b.addVtkCell(12, v, e);
  }
  auto inverted = b.finish();
  EXPECT_EQ(inverted.invertedFixed, hexes.size() / 16);
  RenderSettings s = hardSettings(0, 2, 1);
  s.width = s.height = 48;
  s.camera.eye = {2.2, 1.6, -1.4};
  s.camera.at = {0.5, 0.5, 0.5};
  auto f = smoothField(clean, {0, 0, 0}, 1);
  auto a = test::renderOnGpu(clean, f, s), c = test::renderOnGpu(inverted, f, s);
  test::expectImagesClose("inverted_input", a.image, c.image, {1e-6, 1e-5});
}

// Two blocks that should touch but do not share vertices, with a tiny gap or overlap: both shells
// sit on one rank; the image must match the welded block within what the sliver contributes.
TEST(HardCases, TinyGapsAndOverlapsBetweenClusters) {
  for (double gap : {1e-6, -1e-6, 0.0}) {
    auto left = ref::test::cubeMesh(Split::Tets6, 2, 0.5, {0, 0, 0});
    auto right = ref::test::cubeMesh(Split::Hex, 2, 0.5, {0.5 + gap, 0, 0});
    mesh::UnstructuredMesh both = left;
    mesh::append(both, right);
    auto welded = ref::test::cubeMesh(Split::Hex, 2, 0.5, {0, 0, 0});
    mesh::append(welded, ref::test::cubeMesh(Split::Hex, 2, 0.5, {0.5, 0, 0}));
    RenderSettings s = hardSettings(0, 2, 1);
    s.width = s.height = 40;
    s.camera.eye = {0.5, -2.5, 0.7};
    s.camera.at = {0.5, 0.25, 0.25};
    auto f = smoothField(both, {0, 0, 0}, 1);
    auto g = test::renderOnGpu(both, f, s);
    EXPECT_EQ(g.frame.counters.lostRays, 0u);
    auto reference = test::renderReference(both, f, s);
    test::expectImagesClose("gap_" + std::to_string(gap), reference, g.image);
    // Inside a 1e-6 overlap two boundaries lie within float rounding of each other: up to 0.5% of
    // rays may put one sample on the other side of them.
    RayTolerance tol;
    tol.checkSegments = false;
    tol.tieFraction = 5e-3;
    expectRaysMatch("gap_rays_" + std::to_string(gap), both, f, hardSettings(0, 2, 1), 4, 10000,
                    tol);
  }
}

TEST(HardCases, AClusterOfOneElement) {
  for (mesh::CellType t : mesh::kAllCellTypes) {
    auto m = ref::test::singleElement(t, ref::test::referenceCorners(t));
    expectRaysMatch("one_" + std::string(mesh::cellTypeName(t)), m, smoothField(m, {0, 0, 0}, 1),
                    hardSettings(0, 2, 1), 2, 3000);
  }
}

TEST(HardCases, CameraInsideTheVolume) {
  auto m = ref::test::cubeMesh(Split::Tets5, 4);
  auto f = smoothField(m, {0, 0, 0}, 1);
  RenderSettings s = hardSettings(0, 2, 1);
  s.width = s.height = 48;
  for (glm::dvec3 eye :
       {glm::dvec3(0.5, 0.5, 0.5), glm::dvec3(0.31, 0.62, 0.125), glm::dvec3(0.5, 0.5, 0.25)}) {
    s.camera.eye = eye;
    s.camera.at = eye + glm::dvec3(0.3, 0.2, 0.1);
    s.camera.fovyDeg = 90;
    auto g = test::renderOnGpu(m, f, s);
    EXPECT_EQ(g.frame.counters.lostRays, 0u);
    EXPECT_EQ(g.frame.counters.cameraInside, uint32_t(s.width * s.height));
    test::expectImagesClose("camera_inside", test::renderReference(m, f, s), g.image);
  }
}

TEST(HardCases, FullyOpaqueAndFullyTransparent) {
  auto m = ref::test::cubeMesh(Split::Wedges, 3);
  auto f = smoothField(m, {0, 0, 0}, 1);
  RenderSettings s = cubeView(40);
  s.transferFunction.opacityScale = 1e4;  // opaque at the first sample
  s.earlyTermination = 0.99;
  auto opaque = test::renderOnGpu(m, f, s);
  test::expectImagesClose("fully_opaque", test::renderReference(m, f, s), opaque.image,
                          {1.0 / 255, 0.02});
  s.transferFunction.opacityScale = 0.0;
  auto clear = test::renderOnGpu(m, f, s);
  EXPECT_EQ(clear.frame.counters.fragments, 0u);  // zero-opacity fragments are dropped
  for (const auto& p : clear.image.pixels) EXPECT_EQ(p, glm::vec4(0.0f));
}

// Early termination stops a ray's walk once its opacity reaches the threshold: in a dense medium
// most of the samples and element steps are skipped, and no pixel changes by more than what the
// remaining transmittance (1 - threshold) could still have added.
TEST(HardCases, EarlyTerminationStopsTheWalk) {
  auto m = ref::test::cubeMesh(Split::Tets5, 6);
  auto f = smoothField(m, {0, 0, 0}, 1);
  RenderSettings s = cubeView(40);
  s.transferFunction.opacityScale = 40.0;  // a ray saturates within a few elements
  s.earlyTermination = 2.0;
  auto full = test::renderOnGpu(m, f, s);
  s.earlyTermination = 0.99;
  auto stopped = test::renderOnGpu(m, f, s);
  EXPECT_EQ(stopped.validationErrors, 0u);
  EXPECT_EQ(stopped.frame.counters.lostRays, 0u);
  EXPECT_LT(stopped.frame.counters.samples * 3, full.frame.counters.samples);
  EXPECT_LT(stopped.frame.counters.elementSteps * 2, full.frame.counters.elementSteps);
  double worst = 0;
  for (size_t i = 0; i < full.image.pixels.size(); ++i)
    for (int c = 0; c < 4; ++c)
      worst =
          std::max(worst, double(std::abs(full.image.pixels[i][c] - stopped.image.pixels[i][c])));
  EXPECT_LE(worst, 0.01 + 1e-6);
  EXPECT_GT(worst, 0.0);  // it did stop early somewhere
}

TEST(HardCases, NanAndInfInScalars) {
  auto m = ref::test::cubeMesh(Split::Tets6, 4);
  auto f = smoothField(m, {0, 0, 0}, 1);
  for (size_t i = 0; i < f.size(); i += 7) f[i] = (i % 2) ? NAN : INFINITY;
  RenderSettings s = cubeView(40);
  auto g = test::renderOnGpu(m, f, s);
  auto e = test::expectImagesClose("nan_scalars", test::renderReference(m, f, s), g.image);
  EXPECT_EQ(e.nanPixels, 0);
  expectRaysMatch("nan_scalars_rays", m, f, hardSettings(0, 2, 1), 4);
}

// Many shells on one rank (unwelded slabs): a ray along z crosses 200 of them.
TEST(HardCases, HundredsOfFragmentsPerPixel) {
  mesh::UnstructuredMesh slabs;
  for (int k = 0; k < 200; ++k)
    mesh::append(slabs, ref::test::cubeMesh(Split::Tets6, 1, 1.0, {0, 0, 2.0 * k}));
  for (auto& p : slabs.points) p.z *= 0.01;
  auto f = ref::test::pointField(slabs, [](const glm::dvec3& p) { return p.x + p.z; });
  RenderSettings s = hardSettings(0, 5, 1);
  s.dt = 0.002;
  s.transferFunction.unitDistance = 40;
  std::vector<render::WorldRay> rays;
  for (int i = 0; i < 64; ++i)
    rays.push_back({glm::dvec3(0.1 + 0.0123 * i, 0.37, -1.0), glm::dvec3(0, 0, 1)});
  auto c = test::compareRays(slabs, f, s, rays);
  EXPECT_EQ(c.lost, 0u);
  EXPECT_EQ(c.segmentCountMismatches, 0u);
  EXPECT_LT(c.maxColorError, 2e-4);
  auto g = test::renderOnGpu(slabs, f, [&] {
    RenderSettings t = s;
    t.width = t.height = 16;
    t.camera.eye = {0.5, 0.5, -1};
    t.camera.at = {0.5, 0.5, 1};
    t.camera.up = {0, 1, 0};
    t.camera.fovyDeg = 10;
    t.keepSegments = true;
    return t;
  }());
  const auto& centre = g.segments[8 * 16 + 8];
  EXPECT_EQ(centre.size(), 200u);  // one segment per slab, front to back
  for (size_t i = 1; i < centre.size(); ++i) EXPECT_LT(centre[i - 1].tEntry, centre[i].tEntry);
}

// Every march has a step bound: a tiny bound stops rays (counted) instead of running on.
TEST(HardCases, StepBoundTerminates) {
  auto m = ref::test::cubeMesh(Split::Tets6, 6);
  RenderSettings s = cubeView(24);
  s.maxElementSteps = 3;
  auto g = test::renderOnGpu(m, smoothField(m, {0, 0, 0}, 1), s);
  EXPECT_GT(g.frame.counters.stepLimitHits, 0u);
  EXPECT_EQ(g.frame.counters.lostRays, 0u);
}

// Data sets far from unit size: the device's exact predicates multiply up to three coordinates in
// float, which overflowed (sides of 1e13) or underflowed (1e-18) until preparation scaled such data
// sets by a power of two (prep::GlobalFrame::scale). Each scaled cube matches the reference; scaled
// by a power of two, its device coordinates and so its image equal the unit cube's bit for bit.
TEST(HardCases, DataSetsFarFromUnitSize) {
  const RenderSettings unitView = cubeView(32);
  auto unit = ref::test::cubeMesh(Split::Tets5, 3);
  const auto unitImage = test::renderOnGpu(unit, smoothField(unit, {0, 0, 0}, 1), unitView).image;
  for (double k : {0x1p50, 0x1p-66, 1e15, 1e-20}) {
    auto m = ref::test::cubeMesh(Split::Tets5, 3, k);
    auto f = smoothField(m, {0, 0, 0}, k);
    RenderSettings s = unitView;
    s.camera.eye *= k;
    s.camera.at *= k;
    s.dt *= k;
    s.transferFunction.unitDistance *= k;
    auto g = test::renderOnGpu(m, f, s);
    EXPECT_EQ(g.frame.counters.lostRays, 0u) << k;
    auto e = test::expectImagesClose("scale_" + std::to_string(std::ilogb(k)),
                                     test::renderReference(m, f, s), g.image);
    EXPECT_EQ(e.nanPixels, 0) << k;
    if (k == 0x1p50 || k == 0x1p-66) {
      EXPECT_EQ(g.image.pixels, unitImage.pixels) << k;
    }
  }
}

// Points that no element uses (those of skipped line or surface cells, say) are not part of the
// volume, however far they lie: one at 1e38 and one at 1e300, beyond float, leave the bounds, the
// device frame and the image as they are without them (within the usual reference tolerance).
TEST(HardCases, FarPointsNoElementUsesAreLeftOut) {
  const RenderSettings s = cubeView(32);
  auto m = ref::test::cubeMesh(Split::Tets5, 3);
  auto f = smoothField(m, {0, 0, 0}, 1);
  const scene::Image clean = test::renderReference(m, f, s);
  const mesh::Bounds before = m.bounds();
  m.points.push_back({1e38, 0.5, 0.5});
  m.points.push_back({-1e300, 1e300, 0.5});
  f.insert(f.end(), {1e30f, -1e30f});
  EXPECT_EQ(m.bounds().lo, before.lo);
  EXPECT_EQ(m.bounds().hi, before.hi);
  auto g = test::renderOnGpu(m, f, s);
  EXPECT_EQ(g.frame.counters.lostRays, 0u);
  EXPECT_EQ(test::expectImagesClose("far_unused_points", clean, g.image).nanPixels, 0);
  // The shell's boxes stay as tight as the cube's (padded to ~1e-4 of a triangle): one stretched
  // by a far point would make every ray test every shell triangle.
  const prep::PreparedRank r =
      prep::prepareRank(m, prep::makeGlobalFrame(m.bounds()), prep::PrepOptions{}).rank;
  for (const VkAabbPositionsKHR& b : shellBoxes(r, r.positions))
    EXPECT_LT(std::max({b.maxX - b.minX, b.maxY - b.minY, b.maxZ - b.minZ}), 0.5f);
}

// Samples sit at t = k dt in float, and the samples of one walk are not bounded otherwise: a step
// finer than the farthest corner's distance over 2^24 would repeat positions and, past 2^32
// steps, wrap the device's sample index and never end. It is refused, naming --step; the finest
// allowed step renders.
TEST(HardCases, StepFinerThanFloatResolvesIsRefused) {
  mesh::Bounds b;
  b.extend({1, 1, 1});
  b.extend({2, 2, 2});
  EXPECT_DOUBLE_EQ(finestStep({0, 0, 0}, b), std::sqrt(12.0) * 0x1p-24);
  EXPECT_EQ(finestStep({0, 0, 0}, mesh::Bounds{}), 0.0);
  auto m = ref::test::cubeMesh(Split::Tets5, 1);
  auto f = smoothField(m, {0, 0, 0}, 1);
  RenderSettings s = cubeView(8);
  const double finest = finestStep(s.camera.eye, m.bounds());
  for (double dt : {1e-9, 0.5 * finest, double(INFINITY)}) {
    s.dt = dt;
    try {
      test::renderOnGpu(m, f, s);
      ADD_FAILURE() << "dt " << dt << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("--step"), std::string::npos) << e.what();
    }
  }
  s.width = s.height = 2;      // the finest step: about 2^24 samples for each of 4 rays
  s.dt = finest * (1 + 1e-9);  // the renderer measures from rebased positions: rounding apart
  auto g = test::renderOnGpu(m, f, s);
  EXPECT_EQ(g.frame.counters.lostRays, 0u);
}

// Sampled half an element apart, a mesh of a few elements a side takes a dozen samples across and
// the grid t = k dt shows as nested rings; the default step is capped at the diagonal / 256,
// which brings the image close to element-exact integration.
TEST(HardCases, CoarseMeshesAreSampledAt256StepsAcrossByDefault) {
  mesh::Bounds unit;
  unit.extend({0, 0, 0});
  unit.extend({1, 1, 1});
  EXPECT_DOUBLE_EQ(scene::defaultStep(0.25, unit), std::sqrt(3.0) / 256);
  EXPECT_DOUBLE_EQ(scene::defaultStep(0.001, unit), 0.0005);  // fine meshes keep half an element
  EXPECT_DOUBLE_EQ(scene::defaultStep(0.25, mesh::Bounds{}), 0.125);
  auto m = ref::test::cubeMesh(Split::Hex, 4);
  auto f = smoothField(m, {0, 0, 0}, 1);
  RenderSettings s = cubeView(48);
  s.integration = Integration::ElementExact;
  const scene::Image exact = test::renderOnGpu(m, f, s).image;
  auto maxDiff = [&](double dt) {
    s.integration = Integration::Sampled;
    s.dt = dt;
    const scene::Image g = test::renderOnGpu(m, f, s).image;
    float d = 0;
    for (size_t i = 0; i < g.pixels.size(); ++i)
      for (int c = 0; c < 4; ++c) d = std::max(d, std::abs(g.pixels[i][c] - exact.pixels[i][c]));
    return d;
  };
  const double mean = scene::elementSizeSum(m).mean();
  const float elementRule = maxDiff(scene::elementStep(mean)),
              capped = maxDiff(scene::defaultStep(mean, m.bounds()));
  EXPECT_GT(elementRule, 0.08f);  // 0.11 on lavapipe
  EXPECT_LT(capped, 0.2f * elementRule);
  EXPECT_LT(capped, 0.025f);  // 0.012
}

// A shell larger than the device's acceleration structures hold is refused before the build (on
// the device it would be undefined behaviour). SHELLMARCH_AS_PRIMITIVE_LIMIT stands in for a device
// at the spec's minimum, 2^29 - 1, which no test shell reaches; the grid's shell has 48 triangles.
TEST(HardCases, ShellBeyondTheDevicesPrimitiveLimitIsRefused) {
  RenderSettings s;
  s.width = s.height = 16;
  s.camera.eye = {2.5, 2.0, 1.5};
  s.camera.at = {0.5, 0.5, 0.5};
  s.transferFunction = test::constantTransferFunction({1.0f, 1.0f, 1.0f}, 1.0f, 1.0);
  s.dt = 0.05;
  const mesh::UnstructuredMesh grid = test::hexGrid(2);
  setenv("SHELLMARCH_AS_PRIMITIVE_LIMIT", "47", 1);
  try {
    test::renderOnGpu(grid, "", s);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a shell of 48 triangles on this rank; the device's "
                                         "acceleration structures hold at most 47"),
              std::string::npos)
        << e.what();
  }
  setenv("SHELLMARCH_AS_PRIMITIVE_LIMIT", "48", 1);
  EXPECT_EQ(test::renderOnGpu(grid, "", s).validationErrors, 0u);
  unsetenv("SHELLMARCH_AS_PRIMITIVE_LIMIT");
}

}  // namespace
}  // namespace sm::render
