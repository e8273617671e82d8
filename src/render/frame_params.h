// From a frame's settings to the parameters its shaders read (shared/render_types.h): the camera,
// the transfer function's mapping, shading and clip planes in device coordinates, the scene's and
// the compositor's buffers. Checks what the device cannot honour, naming it.
#pragma once

#include "compositor/deep_compositor.h"
#include "render/frame_resources.h"
#include "render/gpu_scene.h"
#include "render/render_settings.h"
#include "shared/render_types.h"

namespace sm::render {

// `explicitRays`: the frame traces the rays in resources.rays() (Renderer::renderRays) instead of
// camera rays; s.width x s.height must then be their count x 1.
gpu::FrameParams frameParams(const RenderSettings& s, const GpuScene& scene,
                             const comp::DeepCompositor& compositor,
                             const FrameResources& resources, bool explicitRays);

}  // namespace sm::render
