// Gradient shading (Blinn-Phong, headlight) against known answers: a linear field has a constant
// gradient, so every sample along a ray gets the same analytic shaded colour; a trilinear field in
// axis-aligned hexahedra is reproduced exactly, so its gradient is known at every sample.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "render_harness.h"
#include "scene/camera.h"
#include "support/test_meshes.h"

namespace sm::render {
namespace {

RenderSettings shadedSettings() {
  RenderSettings s;
  s.width = s.height = 40;
  s.camera.eye = {1.9, -1.4, 2.3};
  s.camera.at = {0.5, 0.5, 0.5};
  s.camera.up = {0, 0, 1};
  s.camera.fovyDeg = 40;
  s.earlyTermination = 2.0;
  s.shading.enabled = true;
  s.shading.ambient = 0.25;
  s.shading.diffuse = 0.6;
  s.shading.specular = 0.3;
  s.shading.shininess = 8;
  return s;
}

glm::dvec3 shaded(const Shading& sh, glm::dvec3 rgb, glm::dvec3 grad, glm::dvec3 dir) {
  double m = glm::length(grad);
  if (m == 0) return rgb;
  double c = std::abs(glm::dot(grad, dir)) / m;
  return rgb * (sh.ambient + sh.diffuse * c) + glm::dvec3(sh.specular * std::pow(c, sh.shininess));
}

// s = 0.2 + 0.3 x + 0.5 y - 0.4 z through a constant-colour medium: element-exact opacity is
// 1 - exp(-sigma L) and the colour that opacity times the shaded colour, for every cell type.
TEST(Shading, ConstantGradientIsAnalytic) {
  const glm::dvec3 grad(0.3, 0.5, -0.4);
  const glm::dvec3 rgb(0.2, 0.6, 0.9);
  const double sigma = 1.7;
  for (auto [mesh, name] :
       {std::pair{test::hexGrid(3), "hex"}, std::pair{test::kuhnTetGrid(3), "tet"},
        std::pair{test::wedgeGrid(2), "wedge"}, std::pair{test::pyramidGrid(2), "pyramid"}}) {
    RenderSettings s = shadedSettings();
    s.transferFunction = test::constantTransferFunction(glm::vec3(rgb), 1.0f, 1.0 / sigma);
    s.integration = Integration::ElementExact;
    std::vector<float> f;
    for (const auto& p : mesh.points) f.push_back(float(0.2 + glm::dot(grad, p)));
    auto r = test::renderOnGpu(mesh, f, s);
    EXPECT_EQ(r.validationErrors, 0u);
    EXPECT_EQ(r.frame.counters.lostRays, 0u);
    auto cam = scene::cameraFrame(s.camera, s.width, s.height);
    double worst = 0;
    for (int y = 0; y < s.height; ++y) {
      for (int x = 0; x < s.width; ++x) {
        glm::dvec3 d = cam.pixelDirection(x, y);
        double t0, t1;
        test::rayBox(cam.eye, d, glm::dvec3(0.0), glm::dvec3(1.0), t0, t1);
        double alpha = t1 > t0 ? 1.0 - std::exp(-sigma * (t1 - t0)) : 0.0;
        glm::dvec3 want = alpha * shaded(s.shading, rgb, grad, d);
        glm::vec4 got = r.image.at(x, y);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(got[c] - want[c]));
      }
    }
    std::printf("[shading] constant gradient %-8s max abs error %.2g\n", name, worst);
    EXPECT_LT(worst, 1e-3) << name;
  }
}

// s = x y z in hexahedra (trilinear, so interpolated exactly), sampled on the global grid: each
// sample's colour is the transfer function at s shaded with the gradient (yz, xz, xy) there.
TEST(Shading, TrilinearGradientInHexahedra) {
  RenderSettings s = shadedSettings();
  s.transferFunction = scene::makeTransferFunction("cool-to-warm");
  s.transferFunction.lo = 0;
  s.transferFunction.hi = 1;
  s.transferFunction.unitDistance = 0.4;
  s.dt = 0.0071;
  s.integration = Integration::Sampled;
  auto mesh = test::hexGrid(4);
  std::vector<float> f;
  for (const auto& p : mesh.points) f.push_back(float(p.x * p.y * p.z));
  auto r = test::renderOnGpu(mesh, f, s);
  EXPECT_EQ(r.validationErrors, 0u);
  EXPECT_EQ(r.frame.counters.lostRays, 0u);
  auto cam = scene::cameraFrame(s.camera, s.width, s.height);
  const auto& tf = s.transferFunction;
  double sumSq = 0, worst = 0;
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      glm::dvec3 d = cam.pixelDirection(x, y);
      double t0, t1;
      test::rayBox(cam.eye, d, glm::dvec3(0.0), glm::dvec3(1.0), t0, t1);
      glm::dvec4 acc(0.0);
      for (double k = std::ceil(t0 / s.dt); t1 > t0 && k * s.dt < t1; k += 1) {
        glm::dvec3 p = cam.eye + k * s.dt * d;
        glm::dvec4 c = tf.lookup(p.x * p.y * p.z);
        glm::dvec3 rgb = shaded(s.shading, glm::dvec3(c), {p.y * p.z, p.x * p.z, p.x * p.y}, d);
        double a = 1.0 - std::exp(-c.a / tf.unitDistance * s.dt);
        acc += (1.0 - acc.a) * glm::dvec4(rgb * a, a);
      }
      glm::vec4 got = r.image.at(x, y);
      for (int c = 0; c < 4; ++c) {
        double e = std::abs(got[c] - acc[c]);
        sumSq += e * e;
        worst = std::max(worst, e);
      }
    }
  }
  double rmse = std::sqrt(sumSq / (4.0 * s.width * s.height));
  std::printf("[shading] trilinear gradient, hexahedra: RMSE %.2g, max abs %.2g\n", rmse, worst);
  EXPECT_LT(rmse, 1e-4);   // measured 7.5e-7
  EXPECT_LT(worst, 2e-2);  // a sample within rounding of the box boundary may fall either side
}

// Shading off (the default) leaves the pipeline without it: the image equals the unshaded one,
// and turning it on changes it.
TEST(Shading, OffByDefaultAndOnChangesTheImage) {
  RenderSettings s = shadedSettings();
  s.transferFunction = test::constantTransferFunction({0.8f, 0.4f, 0.2f}, 1.0f, 0.5);
  s.dt = 0.01;
  auto mesh = test::kuhnTetGrid(2);
  std::vector<float> f;
  for (const auto& p : mesh.points) f.push_back(float(p.x + 0.5 * p.y));
  auto on = test::renderOnGpu(mesh, f, s);
  s.shading = Shading{};
  EXPECT_FALSE(s.shading.enabled);
  auto off = test::renderOnGpu(mesh, f, s);
  double maxDiff = 0;
  for (size_t i = 0; i < on.image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      maxDiff = std::max(maxDiff, double(std::abs(on.image.pixels[i][c] - off.image.pixels[i][c])));
  EXPECT_GT(maxDiff, 0.05);
  for (const auto& px : off.image.pixels)
    EXPECT_NEAR(px.r, 4.0 * px.b, 1e-5);  // unshaded colour ratio kept
}

}  // namespace
}  // namespace sm::render
