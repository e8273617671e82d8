// One rank's renderer of one data set: the Vulkan context, the data on the device, and a
// compositor and renderer per image size, owned together in the order they depend on each other.
// Every front end renders through one: the render command, the viewer, the in-situ library and
// the benchmarks.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec4.hpp>

#include "comm/communicator.h"
#include "compositor/deep_compositor.h"
#include "prep/prepared_rank.h"
#include "render/gpu_scene.h"
#include "render/renderer.h"
#include "vk/context.h"

namespace sm::session {

struct SessionOptions {
  comp::CompositorOptions lists;  // the compositor's list mode and encoding
  vk::Tracer tracer = vk::Tracer::Auto;
  // Image sizes whose compositor and renderer are kept (the most recently used): the viewer
  // keeps two, so that interaction at a reduced size and the still frames between build nothing.
  int keptSizes = 1;
};

class RankSession {
 public:
  // `context`: the device this rank renders on, made here. `comm`: the ranks that composite
  // together, or nullptr for a rank alone (comm::withPeers); it must outlive the session.
  RankSession(const vk::ContextOptions& context, comm::Communicator* comm,
              SessionOptions options = {});
  // On a context the caller owns, which must outlive the session (benchmarks that render
  // several data sets on one device).
  RankSession(const vk::Context& context, comm::Communicator* comm, SessionOptions options = {});
  ~RankSession();
  RankSession(const RankSession&) = delete;
  RankSession& operator=(const RankSession&) = delete;

  const vk::Context& context() const { return *ctx_; }

  // The data on the device: `rank`, with its positions moved in (render::GpuScene). Replaces an
  // earlier scene, and with it every compositor and renderer.
  render::GpuScene& setScene(const prep::PreparedRank& rank, std::vector<float> positions,
                             render::ShellGeometry shell = render::ShellGeometry::Boxes);
  void releaseScene();
  bool hasScene() const { return scene_ != nullptr; }
  render::GpuScene& scene() const;

  // The renderer for width x height, and its compositor: built on the first frame of a size,
  // taking over the pipelines of the renderer before it (compiling them again costs seconds on
  // lavapipe: they depend on the scene, options and list mode, not on the image size).
  render::Renderer& renderer(int width, int height);
  comp::DeepCompositor& compositor(int width, int height);
  // The same with other lists or another tracer than the session's: the benchmarks compare them
  // over one scene. Kept as the session's own sizes are (SessionOptions::keptSizes).
  render::Renderer& renderer(int width, int height, const comp::CompositorOptions& lists,
                             vk::Tracer tracer);
  comp::DeepCompositor& compositor(int width, int height, const comp::CompositorOptions& lists,
                                   vk::Tracer tracer);
  // Drops every compositor and renderer and the pipelines they share: the next frame builds and
  // compiles anew (benchmarks that time a first frame).
  void releaseRenderers();
  // A frame of s.width x s.height (render::Renderer::render).
  render::FrameResult render(const render::RenderSettings& s, std::vector<glm::vec4> reuse = {});

  // Pipelines compiled for this session's scenes, by every renderer.
  uint64_t pipelinesBuilt() const;
  // Geometry builds and scalar uploads of this session's scenes, those replaced included.
  uint64_t geometryBuilds() const;
  uint64_t scalarUploads() const;

 private:
  struct Target {
    int width = 0, height = 0;
    comp::CompositorOptions lists;
    vk::Tracer tracer = vk::Tracer::Auto;
    std::unique_ptr<comp::DeepCompositor> compositor;
    std::unique_ptr<render::Renderer> renderer;
  };
  Target& target(int width, int height, const comp::CompositorOptions& lists, vk::Tracer tracer);

  // Declaration order is destruction order reversed: renderers go before what they use.
  std::unique_ptr<vk::Context> ownedContext_;
  const vk::Context* ctx_;
  comm::Communicator* comm_;
  SessionOptions options_;
  std::unique_ptr<render::GpuScene> scene_;
  std::shared_ptr<render::PassCache> passes_;  // the pipelines every target's renderer shares
  std::vector<Target> targets_;                // the most recently used last
  uint64_t retiredPipelines_ = 0, retiredBuilds_ = 0, retiredUploads_ = 0;
};

}  // namespace sm::session
