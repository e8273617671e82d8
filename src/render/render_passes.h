// The renderer's stages as pass objects: the stage-split tracer (shell traversal counting / storing
// segments, then marching segments into fragments), the cached two-pass tracer (traversal and
// marching fused, each ray traced once), and the fused single pass used with fixed-length
// fragment lists. Each owns its pipeline, specialised to the scene and the compositor's lists.
#pragma once

#include <cstdint>
#include <memory>

#include "compositor/deep_compositor.h"
#include "render/gpu_scene.h"
#include "render/tracer_pipeline.h"
#include "vk/pipeline.h"

namespace sm::render {

// The compositor's list mode and encoding, as the passes' specialisation constants 100 and 101:
// all a pass needs of the compositor (a pass outlives the compositor it was first built for).
struct ListConstants {
  uint32_t mode = 0, encoding = 0;
  static ListConstants of(const comp::DeepCompositor& c) {
    return {c.modeConstant(), c.encodingConstant()};
  }
  bool operator==(const ListConstants&) const = default;
};

// What a frame's pipelines are specialised for besides the scene (docs/DESIGN.md, "pay only for
// what the scene uses"): each combination is its own pipeline, built on first use.
struct PassOptions {
  bool elementExact = false;
  bool shading = false;
  bool allTypes = false;  // benchmarks: as if every element type were present (no type folding)
  bool clip = false;      // the frame has clip planes
  bool logScale = false;  // the transfer function maps the scalar's logarithm
  static constexpr int kCombinations = 32;
  int index() const {
    return (elementExact ? 1 : 0) + (shading ? 2 : 0) + (allTypes ? 4 : 0) + (clip ? 8 : 0) +
           (logScale ? 16 : 0);
  }
};

std::vector<vk::SpecConstant> sceneSpecialization(const vk::Context& ctx, const GpuScene& scene,
                                                  ListConstants lists, PassOptions options);

// A two-pass stage: one pipeline that counts or stores (a push constant picks the pass; one
// pipeline, not two specialisations, because compiling the tracer is most of a renderer's first
// frame on lavapipe). tracer_passes.glsl says what each pass does.
//   Traversal: the stage-split tracer's traversal, counting then storing segments.
//   Cached: the count pass traces and marches, caching each pixel's first segments and
//     fragments; the store pass traces again the pixels with more segments than cache slots
//     (StoreCachedPass copies the others).
enum class CountStoreKind { Traversal, Cached };

class CountStorePass {
 public:
  CountStorePass(const vk::Context& ctx, const GpuScene& scene, ListConstants lists,
                 vk::Tracer tracer, PassOptions options, CountStoreKind kind);
  void recordCount(VkCommandBuffer cmd, VkDeviceAddress params, int width, int height) const;
  void recordStore(VkCommandBuffer cmd, VkDeviceAddress params, int width, int height) const;

 private:
  TracerPipeline pipeline_;
};

class MarchPass {
 public:
  MarchPass(const vk::Context& ctx, const GpuScene& scene, ListConstants lists,
            PassOptions options);
  void record(VkCommandBuffer cmd, VkDeviceAddress params, int width, int height) const;

 private:
  vk::ComputePipeline pipeline_;
};

// The cached lists' copy: each pixel whose segments all fit in the cache gets its cached fragments
// (and segments, with keepSegments) at its place in the lists (store_cached.comp). A small
// pipeline, so that the tracer's runs only where rays must be traced again.
class StoreCachedPass {
 public:
  StoreCachedPass(const vk::Context& ctx, const GpuScene& scene, ListConstants lists);
  void record(VkCommandBuffer cmd, VkDeviceAddress params, int width, int height) const;

 private:
  vk::ComputePipeline pipeline_;
};

class FusedPass {
 public:
  FusedPass(const vk::Context& ctx, const GpuScene& scene, ListConstants lists, vk::Tracer tracer,
            PassOptions options);
  void record(VkCommandBuffer cmd, VkDeviceAddress params, int width, int height) const;

 private:
  TracerPipeline pipeline_;
};

// A scene's pass objects, each built the first time a frame asks for it. Renderers of the same
// scene and list mode share one (Renderer's constructor takes it), so that a new renderer for
// another image size (the viewer's after a resize) compiles no pipeline: pipelines depend on the
// scene, the options and the compositor's list mode and encoding, not on the image size, and
// compiling the tracer is most of a renderer's first frame on lavapipe (seconds on the demo).
//
// The tracer passes trace with `tracer` (vk::Tracer::Auto: the context's choice).
class PassCache {
 public:
  PassCache(const vk::Context& ctx, const GpuScene& scene, const comp::DeepCompositor& compositor,
            vk::Tracer tracer = vk::Tracer::Auto);
  // Whether passes built for this cache serve `compositor` (the same list mode and encoding) with
  // `tracer` (Auto: the context's).
  bool serves(const GpuScene& scene, const comp::DeepCompositor& compositor,
              vk::Tracer tracer = vk::Tracer::Auto) const;
  vk::Tracer tracer() const { return tracer_; }

  CountStorePass& traversal();
  CountStorePass& cached(PassOptions options);
  StoreCachedPass& storeCached();
  MarchPass& march(PassOptions options);
  FusedPass& fused(PassOptions options);
  uint64_t pipelinesBuilt() const { return built_; }

 private:
  // The pass in `slot`, built from (ctx, scene, lists, args...) the first time.
  template <class Pass, class... Args>
  Pass& ensure(std::unique_ptr<Pass>& slot, Args... args) {
    if (!slot) {
      slot = std::make_unique<Pass>(ctx_, scene_, lists_, args...);
      ++built_;
    }
    return *slot;
  }

  const vk::Context& ctx_;
  const GpuScene& scene_;
  ListConstants lists_;
  vk::Tracer tracer_;
  uint64_t built_ = 0;
  std::unique_ptr<CountStorePass> traversal_;
  std::unique_ptr<CountStorePass> cached_[PassOptions::kCombinations];
  std::unique_ptr<StoreCachedPass> storeCached_;  // one for all: it neither traces nor marches
  std::unique_ptr<MarchPass> march_[PassOptions::kCombinations];
  std::unique_ptr<FusedPass> fused_[PassOptions::kCombinations];
};

}  // namespace sm::render
