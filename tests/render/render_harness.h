// Renders a mesh on the GPU in one call (prepare, upload, render, composite) for image tests.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "compositor/deep_compositor.h"
#include "mesh/unstructured_mesh.h"
#include "prep/prepare.h"
#include "render/renderer.h"
#include "scene/image.h"
#include "vk/context.h"

namespace sm::test {

struct GpuRender {
  scene::Image image;
  render::FrameResult frame;
  uint64_t validationErrors = 0, validationWarnings = 0;
  std::vector<std::vector<gpu::Segment>> segments;       // per pixel (two-pass lists)
  std::vector<std::vector<comp::DcFragment>> fragments;  // per pixel, list order
};

struct GpuRenderOptions {
  bool compact = true;
  render::ShellGeometry shell = render::ShellGeometry::Boxes;
  comp::CompositorOptions lists;
  vk::ContextOptions context;  // the rig's context (the SHELLMARCH_* environment applies too)
};

// One rank's renderer of `mesh` with per-point `values`, kept for several frames (a test that
// renders again, or changes what the device holds between frames). Its context is made with
// whatever SHELLMARCH_* environment is set when the rig is.
struct RenderRig {
  RenderRig(const mesh::UnstructuredMesh& mesh, const std::vector<float>& values, int width,
            int height, const GpuRenderOptions& options = {});
  vk::Context ctx;
  prep::PreparedRank prepared;
  render::GpuScene scene;
  comp::DeepCompositor compositor;
  render::Renderer renderer;
};

// Both tracers (ray queries and the ray tracing pipeline) run the same arithmetic on the same
// pixels, so where the device offers both they must agree bit for bit. Renders `settings` again
// (the camera's rays, or `rays` if given) with the tracer that `first` did not use, and expects the
// same pixels, counters, segment and fragment lists as `frame`, which `first` rendered. Does
// nothing on a device with one tracer.
void expectOtherTracerAgrees(const vk::Context& ctx, const render::GpuScene& scene,
                             comp::DeepCompositor& compositor,
                             const render::RenderSettings& settings, const render::Renderer& first,
                             const render::FrameResult& frame,
                             const std::vector<render::WorldRay>* rays = nullptr);

// Renders `mesh` (one rank) with the scalars of field `field`, step 0 (zeros if absent); the first
// render of each test case also with the other tracer where the device has both
// (expectOtherTracerAgrees).
GpuRender renderOnGpu(const mesh::UnstructuredMesh& mesh, const std::string& field,
                      const render::RenderSettings& settings, const GpuRenderOptions& options = {});
// Same with explicit per-point scalars.
GpuRender renderOnGpu(const mesh::UnstructuredMesh& mesh, const std::vector<float>& values,
                      const render::RenderSettings& settings, const GpuRenderOptions& options = {});

// Ray/box intersection in double: [t0, t1] of the ray (t >= 0) inside [lo, hi]^3, or t1 < t0.
void rayBox(glm::dvec3 o, glm::dvec3 d, glm::dvec3 lo, glm::dvec3 hi, double& t0, double& t1);

// The mesh with its vertices renumbered in shellmarch's global vertex order (position-based, see
// prep/vertex_order.h). Quads are split through their smallest vertex in that order, so the
// reference must see the same numbering to triangulate warped quads as the GPU does.
mesh::UnstructuredMesh inGlobalVertexOrder(const mesh::UnstructuredMesh& mesh);

// The CPU reference's image of the same frame (Grid mode: the same samples as the GPU, whose
// settings must ask for sampled integration).
scene::Image renderReference(const mesh::UnstructuredMesh& mesh, const std::vector<float>& values,
                             const render::RenderSettings& settings);

struct ImageCheck {
  double maxRmse = 1.0 / 255.0;
  double maxAbs = 0.05;
};
// Compares with the reference; on failure writes reference/result/difference PNGs under the test
// output folder and reports where. Returns the error for further checks.
scene::ImageError expectImagesClose(const std::string& name, const scene::Image& reference,
                                    const scene::Image& result, const ImageCheck& check = {});

// A w x h view of the unit cube from (2.1, -1.3, 1.7), viridis over [0, 6]: for fields of the
// kind x + 2y + 3z on cubes of a few cells.
render::RenderSettings cubeView(int width, int height);

// A transfer function with constant colour and opacity (for analytic tests).
scene::TransferFunction constantTransferFunction(glm::vec3 rgb, float opacity, double unitDistance);

// Writes reference, result and difference PNGs for a failed comparison; returns the folder.
std::string writeComparison(const std::string& name, const scene::Image& reference,
                            const scene::Image& result);

}  // namespace sm::test
