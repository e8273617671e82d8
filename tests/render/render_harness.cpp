#include "render_harness.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

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
    : prepared(test::prepared(mesh, options.compact)),
      scene(ctx, prepared, options.shell),
      compositor(ctx, nullptr, width, height, options.lists),
      renderer(ctx, scene, compositor) {
  scene.setScalars(prep::gatherScalars(prepared, values));
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
