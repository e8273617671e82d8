#include "render/render_passes.h"

#include "render_shaders.h"

namespace sm::render {
namespace {

// tracer_passes.glsl's kPass.
constexpr uint32_t kPassConstant = 30;
enum : uint32_t { kPassTraverse = 0, kPassCached = 1, kPassFused = 2 };

std::vector<vk::SpecConstant> withPass(std::vector<vk::SpecConstant> spec, uint32_t pass) {
  spec.push_back({kPassConstant, pass});
  return spec;
}

vk::ComputePipeline makePipeline(const vk::Context& ctx, const char* name,
                                 std::span<const uint32_t> spirv,
                                 std::vector<vk::SpecConstant> spec) {
  return vk::ComputePipeline(ctx, {name, spirv, std::move(spec), sizeof(TracerPush), false});
}

vk::Tracer resolved(const vk::Context& ctx, vk::Tracer t) {
  return t == vk::Tracer::Auto ? ctx.tracer() : t;
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
                               vk::Tracer tracer, PassOptions options, CountStoreKind kind)
    : pipeline_(ctx, scene, tracer,
                kind == CountStoreKind::Cached ? "trace and march (count, store)"
                                               : "traverse (count, store)",
                withPass(sceneSpecialization(ctx, scene, c, options),
                         kind == CountStoreKind::Cached ? kPassCached : kPassTraverse)) {}

void CountStorePass::recordCount(VkCommandBuffer cmd, VkDeviceAddress params, int w, int h) const {
  pipeline_.record(cmd, params, w, h, 0);
}

void CountStorePass::recordStore(VkCommandBuffer cmd, VkDeviceAddress params, int w, int h) const {
  pipeline_.record(cmd, params, w, h, 1);
}

MarchPass::MarchPass(const vk::Context& ctx, const GpuScene& scene, ListConstants c,
                     PassOptions options)
    : pipeline_(
          makePipeline(ctx, "march", spv::march(), sceneSpecialization(ctx, scene, c, options))) {}

void MarchPass::record(VkCommandBuffer cmd, VkDeviceAddress params, int w, int h) const {
  pipeline_.dispatch(cmd, vk::groupsFor(uint64_t(w), 8), vk::groupsFor(uint64_t(h), 8), 1,
                     TracerPush{params});
}

StoreCachedPass::StoreCachedPass(const vk::Context& ctx, const GpuScene& scene, ListConstants c)
    : pipeline_(makePipeline(ctx, "store cached", spv::store_cached(),
                             sceneSpecialization(ctx, scene, c, PassOptions{}))) {}

void StoreCachedPass::record(VkCommandBuffer cmd, VkDeviceAddress params, int w, int h) const {
  pipeline_.dispatchItems(cmd, uint64_t(w) * uint64_t(h), 64, TracerPush{params});
}

FusedPass::FusedPass(const vk::Context& ctx, const GpuScene& scene, ListConstants c,
                     vk::Tracer tracer, PassOptions options)
    : pipeline_(ctx, scene, tracer, "render (fused)",
                withPass(sceneSpecialization(ctx, scene, c, options), kPassFused)) {}

void FusedPass::record(VkCommandBuffer cmd, VkDeviceAddress params, int w, int h) const {
  pipeline_.record(cmd, params, w, h, 0);
}

PassCache::PassCache(const vk::Context& ctx, const GpuScene& scene,
                     const comp::DeepCompositor& compositor, vk::Tracer tracer)
    : ctx_(ctx),
      scene_(scene),
      lists_(ListConstants::of(compositor)),
      tracer_(resolved(ctx, tracer)) {}

bool PassCache::serves(const GpuScene& scene, const comp::DeepCompositor& compositor,
                       vk::Tracer tracer) const {
  return &scene == &scene_ && ListConstants::of(compositor) == lists_ &&
         resolved(ctx_, tracer) == tracer_;
}

CountStorePass& PassCache::traversal() {
  return ensure(traversal_, tracer_, PassOptions{}, CountStoreKind::Traversal);
}

CountStorePass& PassCache::cached(PassOptions options) {
  return ensure(cached_[options.index()], tracer_, options, CountStoreKind::Cached);
}

StoreCachedPass& PassCache::storeCached() {
  return ensure(storeCached_);
}

MarchPass& PassCache::march(PassOptions options) {
  return ensure(march_[options.index()], options);
}

FusedPass& PassCache::fused(PassOptions options) {
  return ensure(fused_[options.index()], tracer_, options);
}

}  // namespace sm::render
