// The device memory a renderer's frames reuse, in one owner: frame parameters, counters, the
// transfer function's tables, segment storage and the segment cache, explicit rays and the
// timestamps that time the passes. Buffers grow on demand and are kept between frames (a frame
// loop allocates nothing once the first frame has run).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "render/preintegration.h"
#include "scene/transfer_function.h"
#include "shared/render_types.h"
#include "vk/buffer.h"
#include "vk/pipeline.h"

namespace sm::render {

class FrameResources {
 public:
  explicit FrameResources(const vk::Context& ctx);

  // The table the device reads, and for element-exact frames the pre-integrated one, for `tf` in
  // device lengths (`scale`: prep::GlobalFrame::scale). The pre-integrated table depends on the
  // transfer function alone: it is rebuilt when that changes, not per frame.
  void setTransferFunction(const scene::TransferFunction& tf, double scale, bool preintegrated);
  VkDeviceAddress transferFunction() const;
  VkDeviceAddress preintegration() const { return preintegration_.address(); }
  const PreintegrationTable& preintegrationTable() const { return preintegrationTable_; }

  VkDeviceAddress params() const { return params_.address(); }
  void writeParams(const gpu::FrameParams& p) { params_.upload(&p, sizeof p); }
  VkDeviceAddress stats() const { return stats_.address(); }
  void resetStats();
  gpu::RenderStats readStats() const;

  // Rays for Renderer::renderRays, in device coordinates.
  void setRays(const std::vector<gpu::RayDesc>& rays);
  VkDeviceAddress rays() const { return rays_.address(); }

  // Storage for `count` segments (at least one), and the segment lists of the last frame: how
  // many, and whether they were written (lastSegments()).
  VkDeviceAddress segments(uint64_t count);
  void noteSegments(uint64_t total, bool kept);
  bool lastSegmentsKept() const { return lastSegmentsKept_ && segments_.valid(); }
  // The last frame's segments, in list order (lastSegmentsKept() frames only).
  std::vector<gpu::Segment> lastSegments() const;

  // Whether a segment cache of `bytes` is there; false when the device has no room for it (a
  // size that failed once is not tried again). The cache is an optimisation: without it the
  // stage-split passes render the same frame.
  bool ensureSegmentCache(uint64_t bytes);
  VkDeviceAddress segmentCache() const { return segmentCache_.address(); }

  // One submission, timed: `record` calls `mark` between its stages. Returns each stage's device
  // milliseconds (one more than the marks, at most 7). Earlier submissions' writes (the scan's
  // offsets, parameters rewritten since) are made visible to the recorded work first.
  using Mark = std::function<void()>;
  std::vector<double> timedSubmit(const std::function<void(VkCommandBuffer, const Mark&)>& record);
  // timedSubmit with one stage.
  double timedSubmit(const std::function<void(VkCommandBuffer)>& record);

 private:
  const vk::Context& ctx_;
  vk::Buffer params_, stats_, transferFunction_, preintegration_, segments_, segmentCache_, rays_;
  uint64_t preintegrationKey_ = 0;
  PreintegrationTable preintegrationTable_;
  uint64_t lastSegmentTotal_ = 0;
  bool lastSegmentsKept_ = false;
  uint64_t failedCacheBytes_ = 0;  // the smallest segment cache the device had no room for
  vk::TimestampQueries timestamps_;
};

}  // namespace sm::render
