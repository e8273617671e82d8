#include "render/list_modes.h"

#include <algorithm>

#include "common/timer.h"
#include "vk/buffer.h"

namespace sm::render {
namespace {

// After a counting pass: prefix sum over the counts (the lists' offsets), storage for the
// segments when they are kept, and the parameters for the next pass.
void scanCounts(FrameWork& f, bool keepSegments) {
  const Timer scan;
  f.out.segments = f.compositor.prepareLists();
  f.out.timings.scanMs = scan.ms();
  f.resources.noteSegments(f.out.segments, keepSegments);
  // The shaders write no segment where the address is 0.
  f.params.segments = keepSegments ? f.resources.segments(f.out.segments) : 0;
  f.params.fragments = f.compositor.lists().fragments;
  f.resources.writeParams(f.params);
}

uint64_t slotBytes(const RenderSettings& s) {
  return uint64_t(s.width) * uint64_t(s.height) * sizeof(gpu::CachedSegment);
}

}  // namespace

void StageSplitLists::fill(FrameWork& f) const {
  const int w = f.settings.width, h = f.settings.height;
  const VkDeviceAddress params = f.resources.params();
  // Pass 1: count each pixel's segments (the compositor's list capacities).
  CountStorePass& traversal = f.passes.traversal();
  f.resources.writeParams(f.params);
  f.out.timings.traversalMs = f.resources.timedSubmit(
      [&](VkCommandBuffer cmd) { traversal.recordCount(cmd, params, w, h); });
  scanCounts(f, true);
  // Pass 2: store the segments at the scanned offsets, then march them into fragments.
  MarchPass& march = f.passes.march(f.options);
  const std::vector<double> ms =
      f.resources.timedSubmit([&](VkCommandBuffer cmd, const FrameResources::Mark& mark) {
        traversal.recordStore(cmd, params, w, h);
        vk::computeBarrier(cmd);
        mark();
        march.record(cmd, params, w, h);
      });
  f.out.timings.traversalMs += ms[0];
  f.out.timings.marchMs = ms[1];
}

uint32_t CachedLists::slots(const vk::Context& ctx, const RenderSettings& s) {
  constexpr uint64_t kMaxSlots = 4;  // most rays of a rank have fewer segments
  const uint64_t budget = std::min(s.segmentCacheBytes, ctx.deviceMemoryLimit() / 8);
  return uint32_t(std::min(kMaxSlots, budget / std::max<uint64_t>(slotBytes(s), 1)));
}

bool CachedLists::fits(const vk::Context& ctx, FrameResources& resources, const RenderSettings& s) {
  const uint32_t n = slots(ctx, s);
  return n > 0 && resources.ensureSegmentCache(n * slotBytes(s));
}

void CachedLists::fill(FrameWork& f) const {
  const int w = f.settings.width, h = f.settings.height;
  const VkDeviceAddress params = f.resources.params();
  f.out.timings.fused = true;
  f.params.segCacheK = slots(f.ctx, f.settings);
  f.params.segCache = f.resources.segmentCache();
  CountStorePass& pass = f.passes.cached(f.options);
  // Pass 1: trace and march every ray, cache its first segments, count them.
  f.resources.writeParams(f.params);
  f.out.timings.traversalMs =
      f.resources.timedSubmit([&](VkCommandBuffer cmd) { pass.recordCount(cmd, params, w, h); });
  scanCounts(f, f.settings.keepSegments);
  // Pass 2: copy into the lists at the scanned offsets, and trace again the pixels the cache was
  // too short for, if any (the tracer's pipeline, run over every pixel, costs more than the copy).
  const gpu::RenderStats counters = f.resources.readStats();
  StoreCachedPass& store = f.passes.storeCached();
  f.out.timings.marchMs = f.resources.timedSubmit([&](VkCommandBuffer cmd) {
    store.record(cmd, params, w, h);
    // Disjoint pixels: the two passes need no barrier between them.
    if (counters.cacheRetraces > 0) pass.recordStore(cmd, params, w, h);
  });
}

void FixedLists::fill(FrameWork& f) const {
  const VkDeviceAddress params = f.resources.params();
  FusedPass& pass = f.passes.fused(f.options);
  f.resources.writeParams(f.params);
  f.out.timings.traversalMs = f.resources.timedSubmit(
      [&](VkCommandBuffer cmd) { pass.record(cmd, params, f.settings.width, f.settings.height); });
  f.out.timings.fused = true;
}

}  // namespace sm::render
