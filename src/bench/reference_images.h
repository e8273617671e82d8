// CPU reference images for `shellmarch bench render`, computed once per view and kept under the
// work directory (the reference takes minutes on a 300k-element mesh at 1024²).
#pragma once

#include <span>
#include <string>

#include "mesh/unstructured_mesh.h"
#include "ref/reference_renderer.h"
#include "scene/camera.h"
#include "scene/image.h"
#include "scene/transfer_function.h"

namespace sm::app::bench {

struct ReferenceImage {
  scene::Image image;
  double seconds = 0;  // time to render it (0 when read from the cache)
  bool cached = false;
  std::string path;
};

// The reference image of the mesh with these settings: read from cacheDir when a file with the
// same key (mesh, values, view, transfer function, settings) is there, else rendered and stored.
ReferenceImage referenceImage(const ref::ReferenceRenderer& renderer, std::span<const float> values,
                              const scene::Camera& camera, int width, int height,
                              const scene::TransferFunction& tf,
                              const ref::RenderSettings& settings, const std::string& cacheDir);

// The image rounded to 8 bits per channel, as an 8-bit framebuffer would hold it.
scene::Image quantised8(const scene::Image& image);

}  // namespace sm::app::bench
