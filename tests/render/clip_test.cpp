// Clip planes: the homogeneous slab's known answer for the clipped length, images against the CPU
// reference in both integration modes and every tracing path, and rays clipped away whole.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "common/error.h"
#include "ref/reference_renderer.h"
#include "render_harness.h"
#include "scene/camera.h"
#include "test_meshes.h"

namespace sm::render {
namespace {

using ref::test::Split;

// An oblique cut through the unit cube's centre and a cut across x: together they keep a
// wedge-shaped part that no face of the cube bounds alone.
std::vector<scene::ClipPlane> twoCuts() {
  return {{{0.5, 0.5, 0.5}, {1.0, 0.8, -0.6}}, {{0.8, 0.0, 0.0}, {-1.0, 0.0, 0.0}}};
}

RenderSettings slabSettings(double sigma, Integration integration) {
  RenderSettings s;
  s.width = s.height = 48;
  s.camera.eye = {1.9, 2.3, 2.7};
  s.camera.at = {0.5, 0.5, 0.5};
  s.camera.up = {0, 0, 1};
  s.camera.fovyDeg = 40;
  s.transferFunction = test::constantTransferFunction({0.2f, 0.6f, 1.0f}, 1.0f, 1.0 / sigma);
  s.dt = 0.01;
  s.earlyTermination = 2.0;  // off: compare the whole integral
  s.integration = integration;
  s.clipPlanes = twoCuts();
  return s;
}

// Per pixel, the slab's opacity over the clipped part of the cube: 1 - exp(-sigma L) element-exact
// (to the pre-integration table's 1e-3), and sampled the scheme's 1 - exp(-sigma dt)^n for the n
// grid samples in [max(t0, lo), min(t1, hi)), but for a sample within rounding of the cut's ends.
TEST(ClipPlanes, SlabOpacityFollowsTheClippedLength) {
  const double sigma = 1.3;
  for (Integration integration : {Integration::Sampled, Integration::ElementExact}) {
    const bool exact = integration == Integration::ElementExact;
    RenderSettings s = slabSettings(sigma, integration);
    auto r = test::renderOnGpu(ref::test::cubeMesh(Split::Tets5, 3), "", s);
    EXPECT_EQ(r.validationErrors, 0u);
    EXPECT_EQ(r.frame.counters.lostRays, 0u);
    auto cam = scene::cameraFrame(s.camera, s.width, s.height);
    const double tol = exact ? 1e-3 : 1.5 * sigma * s.dt * 0.01 + 2e-5;
    auto scheme = [&](double n) { return 1.0 - std::pow(std::exp(-sigma * s.dt), n); };
    auto nearGrid = [&](double t) { return std::abs(t - std::round(t / s.dt) * s.dt) <= 1e-5 * t; };
    int cut = 0, whole = 0, moved = 0;
    double worst = 0;
    for (int y = 0; y < s.height; ++y) {
      for (int x = 0; x < s.width; ++x) {
        const glm::dvec3 d = cam.pixelDirection(x, y);
        double t0, t1;
        test::rayBox(cam.eye, d, glm::dvec3(0.0), glm::dvec3(1.0), t0, t1);
        const scene::ClipSpan span = scene::clipSpan(s.clipPlanes, cam.eye, d);
        const double a = std::max(t0, span.lo), b = std::min(t1, span.hi);
        const bool inCube = t1 > t0, kept = b > a;
        cut += inCube && kept && (a > t0 || b < t1);
        whole += inCube && !kept;
        const double expected = !kept   ? 0.0
                                : exact ? 1.0 - std::exp(-sigma * (b - a))
                                        : scheme(std::ceil(b / s.dt) - std::ceil(a / s.dt));
        const double alpha = r.image.at(x, y).a, err = std::abs(alpha - expected);
        if (!exact && kept && err > tol && (nearGrid(a) || nearGrid(b)) &&
            std::min(std::abs(alpha - scheme(std::ceil(b / s.dt) - std::ceil(a / s.dt) - 1)),
                     std::abs(alpha - scheme(std::ceil(b / s.dt) - std::ceil(a / s.dt) + 1))) <=
                tol) {
          ++moved;
          continue;
        }
        worst = std::max(worst, err);
      }
    }
    std::printf(
        "[clip] slab %-8s max |alpha - expected| = %.2g (%d pixels cut, %d clipped away, "
        "%d samples moved)\n",
        exact ? "exact" : "sampled", worst, cut, whole, moved);
    // The cuts matter here: many rays are shortened, many lose the cube entirely.
    EXPECT_GT(cut, s.width * s.height / 10);
    EXPECT_GT(whole, s.width * s.height / 20);
    EXPECT_LT(worst, tol);
    EXPECT_LE(moved, 3);
  }
}

double wavy(const glm::dvec3& p) {
  return std::sin(3.0 * p.x) + p.y * p.y + 0.5 * p.z;
}

RenderSettings wavySettings() {
  RenderSettings s;
  s.width = s.height = 64;
  s.camera.eye = {2.1, -1.3, 1.7};
  s.camera.at = {0.5, 0.5, 0.5};
  s.camera.up = {0, 0, 1};
  s.camera.fovyDeg = 35;
  s.transferFunction = scene::makeTransferFunction("viridis");
  s.transferFunction.lo = -0.2;
  s.transferFunction.hi = 2.0;
  s.transferFunction.unitDistance = 0.25;
  s.dt = 0.0137;
  s.integration = Integration::Sampled;  // the grid reference's samples (exact tests ask for it)
  s.earlyTermination = 2.0;
  s.clipPlanes = twoCuts();
  return s;
}

// Every element type, and a camera inside the volume (its first segment starts at the eye, behind
// a cut): Grid-mode reference at RMSE 1/255, the default tolerance.
TEST(ClipPlanes, SampledImagesMatchTheReference) {
  for (Split split : ref::test::kAllSplits) {
    auto m = ref::test::cubeMesh(split, 3);
    auto f = ref::test::pointField(m, wavy);
    RenderSettings s = wavySettings();
    auto gpu = test::renderOnGpu(m, f, s);
    EXPECT_EQ(gpu.validationErrors, 0u);
    EXPECT_EQ(gpu.frame.counters.lostRays, 0u);
    test::expectImagesClose("clip_" + ref::test::splitName(split), test::renderReference(m, f, s),
                            gpu.image);
  }
  auto m = ref::test::cubeMesh(Split::Hex, 3);
  auto f = ref::test::pointField(m, wavy);
  RenderSettings s = wavySettings();
  s.camera.eye = {0.3, 0.2, 0.4};
  s.camera.at = {0.9, 0.8, 0.6};
  s.camera.fovyDeg = 70;
  s.clipPlanes = {{{0.5, 0.5, 0.5}, {1.0, 1.0, 0.2}}};
  auto gpu = test::renderOnGpu(m, f, s);
  EXPECT_GT(gpu.frame.counters.cameraInside, 0u);
  test::expectImagesClose("clip_inside", test::renderReference(m, f, s), gpu.image);
}

// Element-exact: the clipped pieces against the reference's continuous integral of the clipped
// crossings (a linear field, so the table's interpolation is the only error).
TEST(ClipPlanes, ElementExactMatchesTheContinuousIntegral) {
  for (Split split : {Split::Tets6, Split::Pyramids, Split::Hex}) {
    auto m = ref::test::cubeMesh(split, 3);
    auto lin = [](const glm::dvec3& p) { return p.x + 2 * p.y + 3 * p.z; };
    RenderSettings s = wavySettings();
    s.transferFunction.lo = 0;
    s.transferFunction.hi = 6;
    s.integration = Integration::ElementExact;
    auto gpu = test::renderOnGpu(m, ref::test::pointField(m, lin), s);
    EXPECT_EQ(gpu.frame.counters.lostRays, 0u);
    mesh::UnstructuredMesh ordered = test::inGlobalVertexOrder(m);
    ref::ReferenceRenderer reference(ordered);
    ref::RenderSettings rs;
    rs.mode = ref::RenderMode::Converged;
    rs.clipPlanes = s.clipPlanes;
    auto want = reference.render(s.camera, s.width, s.height, ref::test::pointField(ordered, lin),
                                 s.transferFunction, rs);
    test::ImageCheck tight;
    tight.maxRmse = 1e-4;
    tight.maxAbs = 1e-3;
    test::expectImagesClose("clip_exact_" + ref::test::splitName(split), want.image, gpu.image,
                            tight);
  }
}

// The cached two-pass tracer (default), the stage-split passes (no cache) and fixed-length lists
// (the fused pass) clip alike.
TEST(ClipPlanes, EveryTracingPathClips) {
  auto m = ref::test::cubeMesh(Split::Wedges, 3);
  auto f = ref::test::pointField(m, wavy);
  RenderSettings s = wavySettings();
  const scene::Image want = test::renderReference(m, f, s);
  RenderSettings split = s;
  split.segmentCacheBytes = 0;
  test::expectImagesClose("clip_stage_split", want, test::renderOnGpu(m, f, split).image);
  test::GpuRenderOptions fixed;
  fixed.lists.mode = comp::ListMode::FixedMerge;
  fixed.lists.fixedK = 4;
  test::expectImagesClose("clip_fixed_lists", want, test::renderOnGpu(m, f, s, fixed).image);
}

// A plane that keeps all of the volume changes nothing, bit for bit; one that keeps none of it
// leaves the image empty and the rays untraced (no shell query, no sample).
TEST(ClipPlanes, AllOrNothing) {
  auto m = ref::test::cubeMesh(Split::Tets5, 3);
  auto f = ref::test::pointField(m, wavy);
  RenderSettings s = wavySettings();
  s.clipPlanes.clear();
  auto plain = test::renderOnGpu(m, f, s);
  s.clipPlanes = {{{-0.5, 0.0, 0.0}, {1.0, 0.1, 0.0}}};
  auto all = test::renderOnGpu(m, f, s);
  EXPECT_EQ(all.frame.counters.samples, plain.frame.counters.samples);
  EXPECT_EQ(scene::compareImages(plain.image, all.image).maxAbs, 0.0);
  s.clipPlanes = {{{0.3, 0.0, 0.0}, {1.0, 0.0, 0.0}}, {{0.2, 0.0, 0.0}, {-1.0, 0.0, 0.0}}};
  auto none = test::renderOnGpu(m, f, s);
  EXPECT_EQ(none.validationErrors, 0u);
  EXPECT_EQ(none.frame.counters.samples, 0u);
  EXPECT_EQ(none.frame.counters.shellQueries, 0u);
  EXPECT_EQ(none.frame.fragments, 0u);
  for (const glm::vec4& p : none.image.pixels) EXPECT_EQ(p.a, 0.0f);
}

TEST(ClipPlanes, TheRendererRefusesImpossiblePlanes) {
  auto m = ref::test::cubeMesh(Split::Hex, 1);
  RenderSettings s = wavySettings();
  auto message = [&](std::vector<scene::ClipPlane> planes) {
    s.clipPlanes = std::move(planes);
    try {
      test::renderOnGpu(m, "", s);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(std::vector<scene::ClipPlane>(7)), "--clip: 7 clip planes, at most 6");
  EXPECT_EQ(message({{{0, 0, 0}, {0, 0, 0}}}), "--clip: clip plane 1 has a zero normal");
  EXPECT_EQ(message({{{0, 0, 0}, {0, 0, 1}}, {{NAN, 0, 0}, {0, 0, 1}}}),
            "--clip: clip plane 2 has a non-finite point or normal");
}

}  // namespace
}  // namespace sm::render
