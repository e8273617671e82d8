// What a frame needs besides the scene: image size, camera, transfer function and sampling.
#pragma once

#include <cstdint>
#include <vector>

#include "compositor/deep_compositor.h"
#include "scene/camera.h"
#include "scene/clip_plane.h"
#include "scene/transfer_function.h"

namespace sm::render {

// Fixed-step sampling on the global grid t = k dt (the paper's method), or element-exact
// integration: every element crossing integrated with the pre-integrated transfer function. The
// default is element-exact: 40 to 600 times less error than the default step at about its time
// (docs/ACCURACY.md).
enum class Integration { Sampled, ElementExact };

// Blinn-Phong shading from the scalar gradient with a headlight (off by default: it costs a
// gradient per sample). The colour from the transfer function becomes
// rgb * (ambient + diffuse |n.l|) + specular |n.l|^shininess, n the unit gradient; samples with a
// zero gradient stay unshaded.
struct Shading {
  bool enabled = false;
  double ambient = 0.3, diffuse = 0.7, specular = 0.2, shininess = 20.0;
};
// Throws SettingError "shading" for enabled shading with a negative coefficient or a shininess
// outside [1, 1024].
void checkShading(const Shading& s);

struct RenderSettings {
  int width = 512, height = 512;
  scene::Camera camera;
  scene::TransferFunction transferFunction;
  double dt = 0.01;  // sample spacing along rays, world units (element-exact: longest piece)
  Integration integration = Integration::ElementExact;
  Shading shading;
  // Up to scene::kMaxClipPlanes planes; each keeps the half-space its normal points into.
  std::vector<scene::ClipPlane> clipPlanes;
  // Benchmarks only: pipelines specialised for every element type, whatever the scene holds, to
  // measure what specialisation saves.
  bool allTypePipelines = false;
  double earlyTermination = 0.99;       // stop a ray once this opaque
  uint32_t maxSegments = 1u << 16;      // per ray: traversal bound
  uint32_t maxElementSteps = 1u << 16;  // per segment: march bound (real rays need far fewer)
  // Two-pass lists: device memory for caching each pixel's first segments between the counting
  // and the storing pass (up to 4 per pixel), so that each ray is traced once. When not even one
  // slot per pixel fits, or with 0, the stage-split passes run instead (traversal twice, then
  // marching), which also time traversal and marching apart.
  uint64_t segmentCacheBytes = uint64_t(256) << 20;
  // Cached two-pass frames: also write each pixel's segment list (Renderer::lastSegments(), for
  // tests and diagnostics). Off, only the fragment lists are written: nothing downstream reads the
  // segments of a frame whose marching is done, and on lavapipe writing them was half of the
  // store pass. The stage-split tracer always writes them (its march pass reads them).
  bool keepSegments = false;
  // Deep (exact, the paper's) or single-fragment compositing (IceT-like, for comparison).
  comp::CompositeMethod compositeMethod = comp::CompositeMethod::Deep;
};

}  // namespace sm::render
