#include "render_harness.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "prep/prepare.h"
#include "ref/reference_renderer.h"
#include "support/test_support.h"
#include "vk/context.h"

namespace sm::test {

GpuRender renderOnGpu(const mesh::UnstructuredMesh& input, const std::string& field,
                      const render::RenderSettings& settings, const GpuRenderOptions& options) {
  const mesh::Field* f = input.findField(field);
  std::vector<float> values = f ? f->steps.at(0) : std::vector<float>(input.numPoints(), 0.0f);
  return renderOnGpu(input, values, settings, options);
}

GpuRender renderOnGpu(const mesh::UnstructuredMesh& input, const std::vector<float>& values,
                      const render::RenderSettings& settings, const GpuRenderOptions& options) {
  mesh::UnstructuredMesh m = input;
  auto frame = prep::makeGlobalFrame(m.bounds());
  auto prepared = prep::prepareRank(m, frame, prep::PrepOptions{options.compact}).rank;
  vk::Context ctx;
  render::GpuScene scene(ctx, prepared);
  scene.setScalars(prep::gatherScalars(prepared, values));
  comp::DeepCompositor compositor(ctx, nullptr, settings.width, settings.height, options.lists);
  render::Renderer renderer(ctx, scene, compositor);
  GpuRender out;
  out.frame = renderer.render(settings);
  out.image = scene::Image(settings.width, settings.height);
  out.image.pixels = out.frame.pixels;
  out.segments = renderer.lastSegments();
  out.validationErrors = ctx.validationErrors();
  out.validationWarnings = ctx.validationWarnings();
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

scene::Image renderReference(const mesh::UnstructuredMesh& mesh, const std::vector<float>& values,
                             const render::RenderSettings& s) {
  ref::ReferenceRenderer r(mesh);
  ref::RenderSettings rs;
  rs.dt = s.dt;
  rs.mode = ref::RenderMode::Grid;
  rs.earlyTermination = std::min(s.earlyTermination, 1.0);
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
