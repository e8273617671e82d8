#include "render/render_passes.h"

#include "render_shaders.h"

namespace sm::render {
namespace {

struct Push {
  uint64_t params;
  uint32_t store = 0;  // count/store passes: which of the two (render_cached.comp)
};

void dispatchPixels(const vk::ComputePipeline& p, VkCommandBuffer cmd, VkDeviceAddress params,
                    int w, int h, uint32_t store = 0) {
  p.dispatch(cmd, vk::groupsFor(uint64_t(w), 8), vk::groupsFor(uint64_t(h), 8), 1,
             Push{params, store});
}

vk::ComputePipeline makePipeline(const vk::Context& ctx, const char* name,
                                 std::span<const uint32_t> spirv,
                                 std::vector<vk::SpecConstant> spec, bool tlas,
                                 const GpuScene& scene) {
  vk::ComputePipeline p(ctx, {name, spirv, std::move(spec), sizeof(Push), tlas});
  if (tlas) p.setAccelerationStructure(scene.tlas());
  return p;
}

}  // namespace

std::vector<vk::SpecConstant> sceneSpecialization(const vk::Context& ctx, const GpuScene& scene,
                                                  ListConstants lists, PassOptions options) {
  return {{0, scene.compact() ? 1u : 0u},
          {1, options.allTypes ? 0xFu : scene.typesPresent()},
          {10, ctx.hasFloat64() ? 1u : 0u},
          {11, scene.shellGeometry() == ShellGeometry::Boxes ? 1u : 0u},
          {12, options.elementExact ? 1u : 0u},
          {13, options.shading ? 1u : 0u},
          {14, options.clip ? 1u : 0u},
          {15, options.logScale ? 1u : 0u},
          {100, lists.mode},
          {101, lists.encoding}};
}

CountStorePass::CountStorePass(const vk::Context& ctx, const GpuScene& scene, ListConstants c,
                               PassOptions options, CountStoreKind kind) {
  const bool cached = kind == CountStoreKind::Cached;
  const auto spirv = cached ? spv::render_cached() : spv::traverse();
  pipeline_ =
      makePipeline(ctx, cached ? "trace and march (count, store)" : "traverse (count, store)",
                   spirv, sceneSpecialization(ctx, scene, c, options), true, scene);
}

void CountStorePass::recordCount(VkCommandBuffer cmd, VkDeviceAddress params, int w, int h) const {
  dispatchPixels(pipeline_, cmd, params, w, h, 0);
}

void CountStorePass::recordStore(VkCommandBuffer cmd, VkDeviceAddress params, int w, int h) const {
  dispatchPixels(pipeline_, cmd, params, w, h, 1);
}

MarchPass::MarchPass(const vk::Context& ctx, const GpuScene& scene, ListConstants c,
                     PassOptions options)
    : pipeline_(makePipeline(ctx, "march", spv::march(),
                             sceneSpecialization(ctx, scene, c, options), false, scene)) {}

void MarchPass::record(VkCommandBuffer cmd, VkDeviceAddress params, int w, int h) const {
  dispatchPixels(pipeline_, cmd, params, w, h);
}

StoreCachedPass::StoreCachedPass(const vk::Context& ctx, const GpuScene& scene, ListConstants c)
    : pipeline_(makePipeline(ctx, "store cached", spv::store_cached(),
                             sceneSpecialization(ctx, scene, c, PassOptions{}), false, scene)) {}

void StoreCachedPass::record(VkCommandBuffer cmd, VkDeviceAddress params, int w, int h) const {
  pipeline_.dispatchItems(cmd, uint64_t(w) * uint64_t(h), 64, Push{params});
}

FusedPass::FusedPass(const vk::Context& ctx, const GpuScene& scene, ListConstants c,
                     PassOptions options)
    : pipeline_(makePipeline(ctx, "render (fused)", spv::render_fused(),
                             sceneSpecialization(ctx, scene, c, options), true, scene)) {}

void FusedPass::record(VkCommandBuffer cmd, VkDeviceAddress params, int w, int h) const {
  dispatchPixels(pipeline_, cmd, params, w, h);
}

PassCache::PassCache(const vk::Context& ctx, const GpuScene& scene,
                     const comp::DeepCompositor& compositor)
    : ctx_(ctx), scene_(scene), lists_(ListConstants::of(compositor)) {}

bool PassCache::serves(const GpuScene& scene, const comp::DeepCompositor& compositor) const {
  return &scene == &scene_ && ListConstants::of(compositor) == lists_;
}

CountStorePass& PassCache::traversal() {
  return ensure(traversal_, PassOptions{}, CountStoreKind::Traversal);
}

CountStorePass& PassCache::cached(PassOptions options) {
  return ensure(cached_[options.index()], options, CountStoreKind::Cached);
}

StoreCachedPass& PassCache::storeCached() {
  return ensure(storeCached_);
}

MarchPass& PassCache::march(PassOptions options) {
  return ensure(march_[options.index()], options);
}

FusedPass& PassCache::fused(PassOptions options) {
  return ensure(fused_[options.index()], options);
}

}  // namespace sm::render
