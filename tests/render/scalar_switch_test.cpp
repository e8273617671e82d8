// Changing the field or time step uploads scalars only: the geometry is built once, and every
// frame equals a fresh render of its scalars, whether they came through the prefetcher (read on a
// background thread into the second buffer while a frame renders) or through setScalars. A
// constant field per step gives a homogeneous medium whose opacity is known per pixel.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "common/error.h"
#include "prep/prepare.h"
#include "render/scalar_prefetch.h"
#include "render_harness.h"
#include "scene/camera.h"
#include "support/test_meshes.h"
#include "vk/context.h"

namespace sm::render {
namespace {

constexpr int kSteps = 4;

// "level": the constant (s + 1) / 5 at step s; "ramp": x + y / 2 + s / 4, varying in space.
mesh::UnstructuredMesh steppedCube() {
  mesh::UnstructuredMesh m = test::kuhnTetGrid(3);
  mesh::Field level{"level", {}}, ramp{"ramp", {}};
  for (int s = 0; s < kSteps; ++s) {
    level.steps.emplace_back(m.numPoints(), float(s + 1) / 5.0f);
    std::vector<float>& r = ramp.steps.emplace_back();
    for (const glm::dvec3& p : m.points) r.push_back(float(p.x + p.y / 2 + s / 4.0));
  }
  m.fields = {level, ramp};
  return m;
}

// White, opacity equal to the normalised scalar: sigma = x / unitDistance.
RenderSettings settings() {
  RenderSettings s;
  s.width = 40;
  s.height = 32;
  s.camera.eye = {2.1, -1.7, 1.6};
  s.camera.at = {0.5, 0.5, 0.5};
  s.camera.up = {0, 0, 1};
  s.camera.fovyDeg = 35;
  s.transferFunction = test::constantTransferFunction({1.0f, 1.0f, 1.0f}, 1.0f, 0.5);
  for (size_t i = 0; i < s.transferFunction.table.size(); ++i)
    s.transferFunction.table[i].a = float(i) / float(s.transferFunction.table.size() - 1);
  s.transferFunction.lo = 0.0;
  s.transferFunction.hi = 2.0;
  s.dt = 0.02;
  // The sampled scheme's opacities (below).
  s.integration = Integration::Sampled;
  s.earlyTermination = 2.0;  // off: the whole integral
  return s;
}

// Opacity of a homogeneous unit cube of extinction sigma: 1 - exp(-sigma dt)^k, k the samples
// t = j dt inside the cube (the slab test's scheme).
void expectHomogeneous(const scene::Image& img, const RenderSettings& s, double sigma) {
  auto cam = scene::cameraFrame(s.camera, s.width, s.height);
  double worst = 0;
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      glm::dvec3 d = cam.pixelDirection(x, y);
      double t0 = 0, t1 = 1e300;
      for (int a = 0; a < 3; ++a) {
        double ta = -cam.eye[a] / d[a], tb = (1.0 - cam.eye[a]) / d[a];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
      }
      double k = t1 > t0 ? std::ceil(t1 / s.dt) - std::ceil(t0 / s.dt) : 0.0;
      worst = std::max(worst, std::abs(img.at(x, y).a - (1.0 - std::exp(-sigma * s.dt * k))));
    }
  }
  EXPECT_LT(worst, 1.5 * sigma * s.dt * 0.01 + 2e-5) << "sigma " << sigma;
}

struct Switch {
  const char* field;
  int step;
};
const Switch kSequence[] = {{"level", 0}, {"level", 2}, {"ramp", 1}, {"level", 3},
                            {"ramp", 3},  {"ramp", 0},  {"level", 1}};

std::vector<float> valuesOf(const mesh::UnstructuredMesh& m, const Switch& sw) {
  return m.findField(sw.field)->steps.at(sw.step);
}

double maxAbsDiff(const scene::Image& a, const scene::Image& b) {
  double d = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 4; ++c) d = std::max(d, double(std::abs(a.pixels[i][c] - b.pixels[i][c])));
  return d;
}

class ScalarSwitchTest : public ::testing::TestWithParam<bool> {};  // staging copies or not

// Each switch rendered on a scene of its own (made once for both parameters).
const std::vector<scene::Image>& freshRenders() {
  static const std::vector<scene::Image> images = [] {
    const mesh::UnstructuredMesh input = steppedCube();
    std::vector<scene::Image> out;
    for (const Switch& sw : kSequence)
      out.push_back(test::renderOnGpu(input, valuesOf(input, sw), settings()).image);
    return out;
  }();
  return images;
}

TEST_P(ScalarSwitchTest, ScalarsOnlyAndFramesEqualFreshRenders) {
  const mesh::UnstructuredMesh input = steppedCube();
  const RenderSettings s = settings();
  const std::vector<scene::Image>& fresh = freshRenders();

  mesh::UnstructuredMesh m = input;
  prep::PreparedRank rank =
      prep::prepareRank(m, prep::makeGlobalFrame(input.bounds()), prep::PrepOptions{}).rank;
  vk::ContextOptions options;
  options.forceStaging = GetParam();
  vk::Context ctx(options);
  GpuScene gpu(ctx, rank, std::move(rank.positions));
  comp::DeepCompositor compositor(ctx, nullptr, s.width, s.height, comp::CompositorOptions{});
  Renderer renderer(ctx, gpu, compositor);
  auto load = [&](const Switch& sw) -> ScalarPrefetcher::Load {
    return [&, sw] { return prep::gatherScalars(rank, valuesOf(input, sw)); };
  };
  auto frame = [&] {
    scene::Image img(s.width, s.height);
    img.pixels = renderer.render(s).pixels;
    return img;
  };
  const size_t n = std::size(kSequence);
  {
    ScalarPrefetcher prefetcher(gpu);
    for (size_t i = 0; i < n; ++i) {
      SCOPED_TRACE(testing::Message() << "prefetched frame " << i);
      ScalarSwitch sw = i == 0 ? prefetcher.loadNow(load(kSequence[0])) : prefetcher.swap();
      EXPECT_EQ(sw.prefetched, i > 0);
      if (i + 1 < n) prefetcher.prefetch(load(kSequence[i + 1]));  // runs beside the frame
      scene::Image img = frame();
      EXPECT_LE(maxAbsDiff(img, fresh[i]), 1e-6);
      if (std::string(kSequence[i].field) == "level")
        expectHomogeneous(img, s, double(kSequence[i].step + 1) / 5.0 / 2.0 / 0.5);
    }
  }
  for (size_t i = 0; i < n; ++i) {  // the synchronous path, on the same scene
    SCOPED_TRACE(testing::Message() << "setScalars frame " << i);
    gpu.setScalars(prep::gatherScalars(rank, valuesOf(input, kSequence[i])));
    EXPECT_LE(maxAbsDiff(frame(), fresh[i]), 1e-6);
  }
  EXPECT_EQ(gpu.geometryBuilds(), 1u);
  EXPECT_EQ(gpu.scalarUploads(), 2 * n);
  EXPECT_EQ(ctx.validationErrors(), 0u);
}

INSTANTIATE_TEST_SUITE_P(Uploads, ScalarSwitchTest, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "Staging" : "Mapped"; });

TEST(ScalarPrefetcher, ALoadErrorSurfacesAtTheSwapAndTheSceneStaysUsable) {
  const mesh::UnstructuredMesh input = steppedCube();
  mesh::UnstructuredMesh m = input;
  prep::PreparedRank rank =
      prep::prepareRank(m, prep::makeGlobalFrame(input.bounds()), prep::PrepOptions{}).rank;
  vk::Context ctx;
  GpuScene gpu(ctx, rank, std::move(rank.positions));
  ScalarPrefetcher prefetcher(gpu);
  prefetcher.prefetch([]() -> std::vector<float> { throw FileError("steps.vtu", "truncated"); });
  EXPECT_THROW(prefetcher.swap(), FileError);
  EXPECT_FALSE(prefetcher.pending());
  prefetcher.prefetch([] { return std::vector<float>(3, 0.0f); });  // wrong size: the scene says
  EXPECT_THROW(prefetcher.swap(), Error);
  ScalarSwitch sw =
      prefetcher.loadNow([&] { return prep::gatherScalars(rank, input.fields[0].steps[0]); });
  EXPECT_FALSE(sw.prefetched);
  EXPECT_EQ(gpu.scalarUploads(), 1u);
  EXPECT_EQ(ctx.validationErrors(), 0u);
}

}  // namespace
}  // namespace sm::render
