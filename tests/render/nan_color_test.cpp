// NaN and infinite data (scene::TransferFunction::nanColor and nanOpacity, --nan-color):
// transparent by default, else the NaN colour at its opacity, in both integrations, as the CPU
// reference draws it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "ref/reference_renderer.h"
#include "render_harness.h"
#include "test_meshes.h"

namespace sm::render {
namespace {

using ref::test::Split;

// x + 2y + 3z, NaN inside a ball at the cube's centre and +inf in a corner.
double holed(const glm::dvec3& p) {
  if (glm::length(p - glm::dvec3(0.5)) < 0.3) return std::numeric_limits<double>::quiet_NaN();
  if (p.x > 0.9 && p.y > 0.9) return std::numeric_limits<double>::infinity();
  return p.x + 2 * p.y + 3 * p.z;
}

RenderSettings holedView() {
  RenderSettings s = test::cubeView(48, 40);
  s.transferFunction.lo = 0;
  s.transferFunction.hi = 6;
  s.earlyTermination = 2.0;
  return s;
}

// The reference's image: Grid mode for sampled integration, the converged integral for exact.
scene::Image referenceImage(const mesh::UnstructuredMesh& m, const RenderSettings& s) {
  if (s.integration == Integration::Sampled)
    return test::renderReference(m, ref::test::pointField(m, holed), s);
  const mesh::UnstructuredMesh ordered = test::inGlobalVertexOrder(m);
  ref::ReferenceRenderer reference(ordered);
  ref::RenderSettings rs;
  rs.mode = ref::RenderMode::Converged;
  return reference
      .render(s.camera, s.width, s.height, ref::test::pointField(ordered, holed),
              s.transferFunction, rs)
      .image;
}

// The centre pixel looks through the NaN ball.
glm::vec4 centre(const scene::Image& img) {
  return img.at(img.width / 2, img.height / 2);
}

TEST(NanColor, TransparentByDefaultAndTheColourWhenAsked) {
  for (Integration integration : {Integration::Sampled, Integration::ElementExact})
    for (Split split : {Split::Tets5, Split::Hex}) {
      auto m = ref::test::cubeMesh(split, 5);
      RenderSettings s = holedView();
      s.integration = integration;
      const std::string name =
          std::string(integration == Integration::Sampled ? "sampled_" : "exact_") +
          ref::test::splitName(split);
      auto plain = test::renderOnGpu(m, ref::test::pointField(m, holed), s);
      EXPECT_EQ(plain.validationErrors, 0u);
      test::ImageCheck check;
      if (integration == Integration::ElementExact) check.maxRmse = 2e-3;
      test::expectImagesClose("nan_plain_" + name, referenceImage(m, s), plain.image, check);

      s.transferFunction.nanColor = {0.0f, 1.0f, 0.0f};
      s.transferFunction.nanOpacity = 0.9f;
      auto green = test::renderOnGpu(m, ref::test::pointField(m, holed), s);
      test::expectImagesClose("nan_green_" + name, referenceImage(m, s), green.image, check);
      // Through the ball the NaN colour shows: greener than the same pixel without it.
      const glm::vec4 c = centre(green.image), p = centre(plain.image);
      EXPECT_GT(c.g, c.r + 0.2f) << name;
      EXPECT_GT(c.g, p.g + 0.1f) << name;
    }
}

// A slab of NaN alone: each pixel's opacity is 1 - exp(-sigma L) with sigma the NaN opacity
// over the unit distance, exactly (no table is involved).
TEST(NanColor, ANanSlabFollowsItsOpticalDepth) {
  auto m = ref::test::cubeMesh(Split::Tets6, 3);
  const std::vector<float> nan(m.points.size(), std::numeric_limits<float>::quiet_NaN());
  for (Integration integration : {Integration::Sampled, Integration::ElementExact}) {
    RenderSettings s = holedView();
    s.integration = integration;
    s.dt = 1e-3;
    s.transferFunction.unitDistance = 1.0 / 1.3;  // sigma = 1.3 at opacity 1
    s.transferFunction.nanColor = {1.0f, 0.5f, 0.0f};
    s.transferFunction.nanOpacity = 1.0f;
    auto r = test::renderOnGpu(m, nan, s);
    const scene::CameraFrame cam = scene::cameraFrame(s.camera, s.width, s.height);
    double worst = 0;
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) {
        double t0, t1;
        test::rayBox(cam.pixelOrigin(x, y), cam.pixelDirection(x, y), glm::dvec3(0.0),
                     glm::dvec3(1.0), t0, t1);
        const double expected = 1.0 - std::exp(-1.3 * std::max(0.0, t1 - t0));
        worst = std::max(worst, std::abs(double(r.image.at(x, y).a) - expected));
        EXPECT_NEAR(r.image.at(x, y).g, 0.5 * r.image.at(x, y).a, 1e-5);  // premultiplied
      }
    // Sampled: the grid's samples approximate the length to dt; exact: float rounding only.
    EXPECT_LT(worst, integration == Integration::Sampled ? 3e-3 : 1e-4);
  }
}

}  // namespace
}  // namespace sm::render
