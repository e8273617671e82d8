#include "render_harness.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "common/check.h"
#include "prep/prepare.h"
#include "prep/vertex_order.h"
#include "ref/reference_renderer.h"
#include "support/test_support.h"
#include "vk/context.h"

namespace sm::test {

void rayBox(glm::dvec3 o, glm::dvec3 d, glm::dvec3 lo, glm::dvec3 hi, double& t0, double& t1) {
  t0 = 0;
  t1 = 1e300;
  for (int a = 0; a < 3; ++a) {
    double inv = 1.0 / d[a];
    double ta = (lo[a] - o[a]) * inv, tb = (hi[a] - o[a]) * inv;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
}

GpuRender renderOnGpu(const mesh::UnstructuredMesh& input, const std::string& field,
                      const render::RenderSettings& settings, const GpuRenderOptions& options) {
  const mesh::Field* f = input.findField(field);
  std::vector<float> values = f ? f->steps.at(0) : std::vector<float>(input.numPoints(), 0.0f);
  return renderOnGpu(input, values, settings, options);
}

namespace {

prep::PreparedRank prepared(const mesh::UnstructuredMesh& input, bool compact) {
  mesh::UnstructuredMesh m = input;
  return prep::prepareRank(m, prep::makeGlobalFrame(m.bounds()), prep::PrepOptions{compact}).rank;
}

}  // namespace

RenderRig::RenderRig(const mesh::UnstructuredMesh& mesh, const std::vector<float>& values,
                     int width, int height, const GpuRenderOptions& options)
    : ctx(options.context),
      prepared(test::prepared(mesh, options.compact)),
      scene(ctx, prepared, std::move(prepared.positions), options.shell),
      compositor(ctx, nullptr, width, height, options.lists),
      renderer(ctx, scene, compositor) {
  scene.setScalars(prep::gatherScalars(prepared, values));
}

namespace {

// Per-pixel lists equal bit for bit.
template <typename T>
bool sameBits(const std::vector<std::vector<T>>& a, const std::vector<std::vector<T>>& b) {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(), [](const auto& x, const auto& y) {
           return x.size() == y.size() &&
                  std::memcmp(x.data(), y.data(), x.size() * sizeof(T)) == 0;
         });
}

// The first render of the running test case: where the other tracer renders too. Once per test
// case, not per render: on lavapipe each comparison costs a pipeline compile (about a second),
// and a test's further renders mostly vary data the first already took through both tracers'
// shared code (the ray harness, whose rays aim at hard cases, compares every render).
bool firstRenderOfThisTest() {
  static std::string last;
  const testing::TestInfo* t = testing::UnitTest::GetInstance()->current_test_info();
  const std::string name = t ? std::string(t->test_suite_name()) + "." + t->name() : "";
  if (name == last) return false;
  last = name;
  return true;
}

}  // namespace

render::RenderSettings cubeView(int width, int height) {
  render::RenderSettings s;
  s.width = width;
  s.height = height;
  s.camera.eye = {2.1, -1.3, 1.7};
  s.camera.at = {0.5, 0.5, 0.5};
  s.camera.up = {0, 0, 1};
  s.transferFunction = scene::makeTransferFunction("viridis");
  s.transferFunction.lo = 0;
  s.transferFunction.hi = 6;
  s.transferFunction.unitDistance = 0.25;
  s.dt = 0.0137;
  return s;
}

void expectOtherTracerAgrees(const vk::Context& ctx, const render::GpuScene& scene,
                             comp::DeepCompositor& compositor,
                             const render::RenderSettings& settings, const render::Renderer& first,
                             const render::FrameResult& frame,
                             const std::vector<render::WorldRay>* rays) {
  const vk::Tracer used = first.tracer();
  const vk::Tracer other = used == vk::Tracer::Query ? vk::Tracer::Pipeline : vk::Tracer::Query;
  if (!(other == vk::Tracer::Query ? ctx.hasRayQuery() : ctx.hasRayTracingPipeline())) return;
  const auto segments = first.lastSegments();
  const auto fragments = first.lastFragments();
  render::Renderer second(ctx, scene, compositor, nullptr, other);
  ASSERT_EQ(second.tracer(), other);
  render::FrameResult again = rays ? second.renderRays(settings, *rays) : second.render(settings);
  const std::string what = std::string("the ") + vk::tracerName(other) + " tracer against the " +
                           vk::tracerName(used) + " tracer: ";
  ASSERT_EQ(again.pixels.size(), frame.pixels.size()) << what << "image size";
  for (size_t i = 0; i < frame.pixels.size(); ++i)
    if (std::memcmp(&again.pixels[i], &frame.pixels[i], sizeof(glm::vec4)) != 0) {
      const glm::vec4 a = frame.pixels[i], b = again.pixels[i];
      ADD_FAILURE() << what << "pixel " << i << " differs: (" << a.r << ", " << a.g << ", " << a.b
                    << ", " << a.a << ") against (" << b.r << ", " << b.g << ", " << b.b << ", "
                    << b.a << ")";
      break;
    }
  EXPECT_EQ(std::memcmp(&again.counters, &frame.counters, sizeof(gpu::RenderStats)), 0)
      << what << "counters differ (segments " << frame.counters.segments << " / "
      << again.counters.segments << ", shell queries " << frame.counters.shellQueries << " / "
      << again.counters.shellQueries << ", element steps " << frame.counters.elementSteps << " / "
      << again.counters.elementSteps << ", lost " << frame.counters.lostRays << " / "
      << again.counters.lostRays << ")";
  EXPECT_EQ(again.segments, frame.segments) << what << "segments";
  EXPECT_EQ(again.fragments, frame.fragments) << what << "fragments";
  EXPECT_TRUE(sameBits(segments, second.lastSegments())) << what << "segment lists differ";
  EXPECT_TRUE(sameBits(fragments, second.lastFragments())) << what << "fragment lists differ";
}

GpuRender renderOnGpu(const mesh::UnstructuredMesh& input, const std::vector<float>& values,
                      const render::RenderSettings& settings, const GpuRenderOptions& options) {
  RenderRig rig(input, values, settings.width, settings.height, options);
  GpuRender out;
  out.frame = rig.renderer.render(settings);
  out.image = scene::Image(settings.width, settings.height);
  out.image.pixels = out.frame.pixels;
  out.segments = rig.renderer.lastSegments();
  out.fragments = rig.renderer.lastFragments();
  if (firstRenderOfThisTest())
    expectOtherTracerAgrees(rig.ctx, rig.scene, rig.compositor, settings, rig.renderer, out.frame);
  out.validationErrors = rig.ctx.validationErrors();
  out.validationWarnings = rig.ctx.validationWarnings();
  return out;
}

scene::TransferFunction constantTransferFunction(glm::vec3 rgb, float opacity,
                                                 double unitDistance) {
  scene::TransferFunction tf;
  tf.table.assign(256, glm::vec4(rgb, opacity));
  tf.lo = 0;
  tf.hi = 1;
  tf.unitDistance = unitDistance;
  return tf;
}

std::string writeComparison(const std::string& name, const scene::Image& reference,
                            const scene::Image& result) {
  std::string dir = outputDir(name);
  scene::writePngRgba(dir + "/reference.png", reference);
  scene::writePngRgba(dir + "/result.png", result);
  scene::writePngRgba(dir + "/difference.png", scene::differenceImage(reference, result, 10.0f));
  return dir;
}

mesh::UnstructuredMesh inGlobalVertexOrder(const mesh::UnstructuredMesh& m) {
  std::vector<uint32_t> order =
      prep::globalVertexOrder(m.points, prep::makeGlobalFrame(m.bounds()));
  std::vector<uint32_t> newId(order.size());
  for (size_t i = 0; i < order.size(); ++i) newId[order[i]] = uint32_t(i);
  mesh::UnstructuredMesh out = m;
  for (size_t i = 0; i < order.size(); ++i) out.points[i] = m.points[order[i]];
  for (auto& cells : out.cells)
    for (uint32_t& v : cells) v = newId[v];
  for (size_t f = 0; f < out.fields.size(); ++f)
    for (size_t step = 0; step < out.fields[f].steps.size(); ++step)
      for (size_t i = 0; i < order.size(); ++i)
        out.fields[f].steps[step][i] = m.fields[f].steps[step][order[i]];
  return out;
}

scene::Image renderReference(const mesh::UnstructuredMesh& input,
                             const std::vector<float>& inputValues,
                             const render::RenderSettings& s) {
  mesh::UnstructuredMesh mesh = inGlobalVertexOrder(input);
  std::vector<uint32_t> order =
      prep::globalVertexOrder(input.points, prep::makeGlobalFrame(input.bounds()));
  std::vector<float> values(inputValues.size());
  for (size_t i = 0; i < order.size(); ++i) values[i] = inputValues[order[i]];
  // Grid mode takes the samples of sampled integration: a test comparing with it asks for that.
  SM_CHECK_MSG(s.integration == render::Integration::Sampled,
               "renderReference: the grid reference is sampled integration's");
  ref::ReferenceRenderer r(mesh);
  ref::RenderSettings rs;
  rs.dt = s.dt;
  rs.mode = ref::RenderMode::Grid;
  rs.earlyTermination = std::min(s.earlyTermination, 1.0);
  rs.clipPlanes = s.clipPlanes;
  return r.render(s.camera, s.width, s.height, values, s.transferFunction, rs).image;
}

scene::ImageError expectImagesClose(const std::string& name, const scene::Image& reference,
                                    const scene::Image& result, const ImageCheck& check) {
  scene::ImageError e = scene::compareImages(reference, result);
  bool ok = e.rmse <= check.maxRmse && e.maxAbs <= check.maxAbs && e.nanPixels == 0;
  std::printf("[image] %-32s RMSE %.3g  max abs %.3g  PSNR %.1f dB\n", name.c_str(), e.rmse,
              e.maxAbs, e.psnr);
  EXPECT_TRUE(ok) << name << ": RMSE " << e.rmse << " (limit " << check.maxRmse << "), max abs "
                  << e.maxAbs << " (limit " << check.maxAbs << "), NaN pixels " << e.nanPixels
                  << "; images written to "
                  << (ok ? std::string("-") : writeComparison(name, reference, result));
  return e;
}

}  // namespace sm::test
