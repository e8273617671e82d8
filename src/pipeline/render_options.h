// What one render asks for: the data, camera, transfer function, sampling, fragment lists, device
// and outputs. The command line (cli/scene_options.h), the viewer, the benchmarks and the Python
// module fill it; the pipeline reads it.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "compositor/deep_compositor.h"
#include "pipeline/rank_share.h"
#include "render/render_settings.h"
#include "scene/camera.h"
#include "scene/image.h"
#include "vk/context.h"

namespace sm::app {

struct RenderJob {
  std::string mesh;
  std::string field;       // "" = the first point field
  std::string time = "0";  // step index or "all"
  int width = 512, height = 512;
  std::optional<glm::dvec3> eye, at, up;
  double fovy = 30.0;
  bool parallel = false;                // --parallel (or a parallel --camera file)
  std::optional<double> parallelScale;  // default: the bounding sphere fits (frameBounds)
  std::string view = "iso";
  std::string colormap = "viridis";
  std::optional<std::pair<double, double>> range;
  double opacityScale = 1.0;
  std::optional<double> unitDistance, step;
  double earlyTermination = 0.99;
  glm::vec3 background{0.1f, 0.1f, 0.12f};
  bool transparent = false;  // --background transparent: PNGs keep the frame's alpha
  scene::Background imageBackground() const {
    return transparent ? scene::Background() : scene::Background(background);
  }
  ShareOptions share;
  comp::CompositorOptions lists;
  bool compact = true;
  std::string device;
  vk::Tracer tracer = vk::Tracer::Auto;
  std::string cacheDir;  // "" = shaders in the default folder, no preparation cache; "none"
  std::string out = "shellmarch.png";  // .png or .pfm (float, for comparisons finer than 8 bits)
  comp::CompositeMethod composite = comp::CompositeMethod::Deep;
  render::Integration integration = render::Integration::ElementExact;  // --integration
  render::Shading shading;
  std::vector<scene::ClipPlane> clipPlanes;  // --clip
  // --opacity: replaces the colour map's opacity (for the field rendered; in the viewer, the
  // first field shown)
  std::vector<scene::OpacityPoint> opacityPoints;
  std::optional<glm::vec4> nanColor;  // --nan-color: rgb and opacity of NaN and infinite values
  bool logScale = false;  // --log-scale (in the viewer, for the fields whose range is positive)
  bool allTypePipelines = false;
  std::string l2Heatmap;   // also composite single-fragment; write the L2 difference heatmap here
  std::string heatmaps;    // prefix: fragment-count heatmaps per rank and combined (PNG)
  std::string dumpCounts;  // per-rank, per-pixel fragment counts (compositor/count_dump.h)
  bool stats = false;
  std::string statsJson;  // write statistics as JSON here
  int repeat = 1;         // render the step sequence this many times (benchmarks); images once
  bool prefetch = true;   // read and upload the next step while a frame renders
  bool legend = false;    // draw the colour legend (scene/legend.h) into the images written
  int orbit = 0;          // > 0: the camera turns 360 / orbit degrees about its up axis each frame
  // When set (the Python module), rank 0 hands each frame's image (premultiplied, legend drawn) and
  // its number here instead of writing `out`; scene::toRgba8 turns it into what the PNG holds.
  std::function<void(const scene::Image&, uint64_t number)> frameSink;
};

}  // namespace sm::app
