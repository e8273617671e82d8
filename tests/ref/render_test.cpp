// Rendering known answers (pbrt style): homogeneous slabs in both modes, a linear opacity ramp
// with a closed-form integral, then consistency: a cube split five ways renders alike, Grid mode
// converges to Converged mode, per-cluster fragments composite to the full image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "common/error.h"
#include "ref/reference_renderer.h"
#include "test_meshes.h"

namespace sm::ref {
namespace {

using test::Split;

scene::TransferFunction uniformTf(const glm::vec3& rgb, double opacityScale, bool ramp) {
  scene::TransferFunction tf;
  tf.table.resize(256);
  for (int i = 0; i < 256; ++i) tf.table[i] = glm::vec4(rgb, ramp ? float(i) / 255.0f : 0.5f);
  tf.opacityScale = opacityScale;
  return tf;
}

scene::Camera obliqueCamera() {
  scene::Camera c;
  c.eye = {-1.3, -0.8, 2.2};
  c.at = {0.5, 0.5, 0.5};
  c.up = {0, 0, 1};
  c.fovyDeg = 40.0;
  return c;
}

// A homogeneous cube: opacity 1 - exp(-sigma L) in Converged mode, and (1 - alpha) ^ n with n
// the exact number of grid samples in Grid mode, per pixel.
TEST(Render, HomogeneousSlabKnownAnswers) {
  const glm::vec3 rgb(0.2f, 0.5f, 0.8f);
  const auto tf = uniformTf(rgb, 2.4, false);
  const double sigma = 0.5f * 2.4, dt = 0.037;
  const int size = 32;
  const auto frame = scene::cameraFrame(obliqueCamera(), size, size);
  for (auto [split, n] : {std::pair{Split::Hex, 1},
                          {Split::Tets6, 2},
                          {Split::Tets5, 2},
                          {Split::Pyramids, 1},
                          {Split::Wedges, 1}}) {
    auto m = test::cubeMesh(split, n);
    ReferenceRenderer r(m);
    auto values = test::pointField(m, [](const glm::dvec3&) { return 0.3; });
    RenderSettings grid{.dt = dt};
    RenderSettings converged{.mode = RenderMode::Converged};
    auto gridImage = r.render(obliqueCamera(), size, size, values, tf, grid);
    auto convergedImage = r.render(obliqueCamera(), size, size, values, tf, converged);
    for (int y = 0; y < size; y += 3)
      for (int x = 0; x < size; ++x) {
        glm::dvec3 dir = frame.pixelDirection(x, y);
        Interval box = test::slab(glm::dvec3(0), glm::dvec3(1), frame.eye, dir);
        double length = std::max(0.0, box.tOut - box.tIn);
        int samples = 0;
        for (int k = 0; k * dt < box.tOut; ++k) samples += k * dt >= box.tIn;
        double wantConverged = -std::expm1(-sigma * length);
        double wantGrid = 1.0 - std::pow(std::exp(-sigma * dt), samples);
        auto frags = r.fragments(frame.eye, dir, values, tf, converged);
        ASSERT_EQ(frags.size(), length > 0 ? 1u : 0u) << test::splitName(split);
        if (!frags.empty()) {
          EXPECT_NEAR(frags[0].alpha, wantConverged, 1e-9) << test::splitName(split);
          EXPECT_NEAR(frags[0].color.b, wantConverged * rgb.b, 1e-9) << test::splitName(split);
          EXPECT_NEAR(frags[0].depth, box.tIn, 1e-12) << test::splitName(split);
          EXPECT_NEAR(r.fragments(frame.eye, dir, values, tf, grid)[0].alpha, wantGrid, 1e-12);
        }
        EXPECT_NEAR(convergedImage.image.at(x, y).a, wantConverged, 1e-6);
        EXPECT_NEAR(gridImage.image.at(x, y).a, wantGrid, 1e-6);
        EXPECT_NEAR(gridImage.image.at(x, y).g, wantGrid * rgb.g, 1e-6);
        EXPECT_EQ(gridImage.stats[y * size + x].samples, uint64_t(samples));
      }
  }
}

// Opacity rising linearly with s = z through a tetrahedralised cube: along a ray crossing z from
// 0 to 1 with direction d, the optical depth is scale * 1/2 / d.z in closed form; the Grid answer
// is the product of the model's per-sample transmittances.
TEST(Render, LinearOpacityRampKnownAnswers) {
  const glm::vec3 rgb(0.3f, 0.6f, 0.9f);
  const double scale = 3.0, dt = 0.0123;
  const auto tf = uniformTf(rgb, scale, true);
  auto m = test::cubeMesh(Split::Tets6, 2);
  ReferenceRenderer r(m);
  auto values = test::pointField(m, [](const glm::dvec3& p) { return p.z; });
  for (glm::dvec4 ray : {glm::dvec4(0.3, 0.6, 0.1, -0.2), glm::dvec4(0.5, 0.5, 0.0, 0.0),
                         glm::dvec4(0.8, 0.2, -0.3, 0.25)}) {
    const glm::dvec3 origin(ray.x, ray.y, -1.0), dir = glm::normalize(glm::dvec3(ray.z, ray.w, 1));
    auto converged = r.fragments(origin, dir, values, tf, {.mode = RenderMode::Converged});
    ASSERT_EQ(converged.size(), 1u);
    double want = -std::expm1(-scale * 0.5 / dir.z);
    EXPECT_NEAR(converged[0].alpha, want, 1e-6);
    EXPECT_NEAR(converged[0].color.r, want * rgb.r, 1e-6);
    double transmittance = 1.0;
    for (int k = 0; k * dt < 2.0 / dir.z; ++k)
      if (k * dt >= 1.0 / dir.z)
        transmittance *= std::exp(-tf.extinction(-1.0 + k * dt * dir.z) * dt);
    auto grid = r.fragments(origin, dir, values, tf, {.dt = dt});
    ASSERT_EQ(grid.size(), 1u);
    EXPECT_NEAR(grid[0].alpha, 1.0 - transmittance, 1e-12);
  }
}

// A vertical ray through each reference element with a linear field (dyadic, so exact in float):
// known entry and exit, exact scalars along the ray, and the model's Grid fragment.
TEST(Render, SingleElementsWithALinearField) {
  const std::pair<mesh::CellType, double> exits[] = {{mesh::CellType::Tet, 1.65},
                                                     {mesh::CellType::Pyramid, 1.3},
                                                     {mesh::CellType::Wedge, 2.0},
                                                     {mesh::CellType::Hex, 2.0}};
  auto f = [](const glm::dvec3& p) { return 0.25 + 0.125 * p.x + 0.25 * p.y + 0.375 * p.z; };
  const auto tf = uniformTf({0.5f, 0.25f, 1.0f}, 5.0, true);
  const glm::dvec3 origin(0.2, 0.15, -1.0), dir(0, 0, 1);
  const double dt = 0.01;
  for (auto [type, tOut] : exits) {
    auto m = test::singleElement(type, test::referenceCorners(type));
    ReferenceRenderer r(m);
    auto values = test::pointField(m, f);
    auto cs = r.traceRay(origin, dir);
    ASSERT_EQ(cs.size(), 1u) << mesh::cellTypeName(type);
    EXPECT_NEAR(cs[0].tIn, 1.0, 1e-15) << mesh::cellTypeName(type);
    EXPECT_NEAR(cs[0].tOut, tOut, 1e-15) << mesh::cellTypeName(type);
    double transmittance = 1.0;
    for (int k = 100; k * dt < tOut; ++k) {
      glm::dvec3 p = origin + k * dt * dir;
      double s = r.scalar(type, 0, values, p);
      EXPECT_NEAR(s, f(p), 1e-14) << mesh::cellTypeName(type) << " at t = " << k * dt;
      transmittance *= std::exp(-tf.extinction(f(p)) * dt);
    }
    auto grid = r.fragments(origin, dir, values, tf, {.dt = dt});
    ASSERT_EQ(grid.size(), 1u);
    EXPECT_NEAR(grid[0].alpha, 1.0 - transmittance, 1e-12) << mesh::cellTypeName(type);
  }
}

// Two hexahedra overlapping over half their length (a non-conforming input): every point and
// every grid sample of the overlap counts once, in the element entered first.
TEST(Render, OverlappingElementsCountOnce) {
  mesh::UnstructuredMesh m;
  for (double x0 : {0.0, 0.5})
    for (const auto& c : test::referenceCorners(mesh::CellType::Hex))
      m.points.push_back(c + glm::dvec3(x0, 0, 0));
  auto& hex = m.cells[mesh::typeIndex(mesh::CellType::Hex)];
  for (uint32_t i = 0; i < 16; ++i) hex.push_back(i);
  m.clusters[mesh::typeIndex(mesh::CellType::Hex)] = {0, 1};
  ReferenceRenderer r(m);
  const auto tf = uniformTf({1, 1, 1}, 2.0, false);
  std::vector<float> values(16, 0.5f);
  const glm::dvec3 origin(-1.0, 0.4, 0.7), dir(1, 0, 0);
  auto cs = r.traceRay(origin, dir);
  ASSERT_EQ(cs.size(), 2u);
  auto segs = segments(cs, {});
  ASSERT_EQ(segs.size(), 1u);
  EXPECT_EQ(segs[0].tOut, 2.5);
  const double dt = 0.1, sigma = 1.0;
  auto grid = r.fragments(origin, dir, values, tf, {.dt = dt});
  ASSERT_EQ(grid.size(), 1u);
  EXPECT_NEAR(grid[0].alpha, 1.0 - std::exp(-sigma * dt * 15), 1e-12);  // k = 10 .. 24
  auto converged = r.fragments(origin, dir, values, tf, {.mode = RenderMode::Converged});
  EXPECT_NEAR(converged[0].alpha, -std::expm1(-sigma * 1.5), 1e-9);
}

scene::TransferFunction viridis() {
  auto tf = scene::makeTransferFunction("viridis");
  tf.lo = 0.0;
  tf.hi = 6.0;
  tf.opacityScale = 4.0;
  return tf;
}

scene::Image renderSplit(Split split, const RenderSettings& settings, int size) {
  auto m = test::cubeMesh(split, 2);
  ReferenceRenderer r(m);
  auto values = test::pointField(m, [](const glm::dvec3& p) { return p.x + 2 * p.y + 3 * p.z; });
  return r.render(obliqueCamera(), size, size, values, viridis(), settings).image;
}

TEST(Render, CubeSplitsAgreeInGridMode) {
  auto hex = renderSplit(Split::Hex, {.dt = 0.01}, 32);
  double alphaSum = 0.0;
  for (const auto& p : hex.pixels) alphaSum += p.a;
  EXPECT_GT(alphaSum, 50.0);  // the scene is not empty
  for (Split split : {Split::Tets5, Split::Tets6, Split::Wedges, Split::Pyramids})
    EXPECT_LT(scene::compareImages(hex, renderSplit(split, {.dt = 0.01}, 32)).maxAbs, 1e-6)
        << test::splitName(split);
}

TEST(Render, CubeSplitsAgreeInConvergedMode) {
  RenderSettings converged{.mode = RenderMode::Converged};
  auto hex = renderSplit(Split::Hex, converged, 16);
  for (Split split : {Split::Tets5, Split::Tets6, Split::Wedges, Split::Pyramids})
    EXPECT_LT(scene::compareImages(hex, renderSplit(split, converged, 16)).maxAbs, 3e-6)
        << test::splitName(split);
}

TEST(Render, GridModeConvergesToConvergedMode) {
  auto exact = renderSplit(Split::Tets6, {.mode = RenderMode::Converged}, 16);
  double coarse = scene::compareImages(exact, renderSplit(Split::Tets6, {.dt = 0.04}, 16)).maxAbs;
  double fine = scene::compareImages(exact, renderSplit(Split::Tets6, {.dt = 0.005}, 16)).maxAbs;
  EXPECT_LT(fine, coarse / 4.0);  // first order: 8 times smaller in theory
  EXPECT_LT(fine, 0.02);
}

}  // namespace
}  // namespace sm::ref
