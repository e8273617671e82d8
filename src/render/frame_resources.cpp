#include "render/frame_resources.h"

#include <algorithm>

#include "common/check.h"
#include "common/hash.h"
#include "compositor/device_util.h"
#include "vk/vk_error.h"

namespace sm::render {
namespace {

constexpr uint32_t kTimestamps = 8;

// A constant range maps every value to the table's middle (scene::TransferFunction::lookup); the
// device gets that colour in every entry, so no rounding of the value (float, far from zero) can
// move a lookup off it.
std::vector<glm::vec4> deviceTable(const scene::TransferFunction& tf) {
  if (tf.hi > tf.lo) return tf.table;
  return std::vector<glm::vec4>(tf.table.size(), glm::vec4(tf.lookup(tf.lo)));
}

// Grows `buffer` to hold `bytes`, dropping its contents when it must.
void ensure(const vk::Context& ctx, vk::Buffer& buffer, uint64_t bytes, const char* name) {
  if (!buffer.valid() || buffer.size() < bytes)
    buffer = vk::Buffer(ctx, bytes, vk::kStorageUsage, vk::MemoryUse::Device, name);
}

}  // namespace

FrameResources::FrameResources(const vk::Context& ctx) : ctx_(ctx), timestamps_(ctx, kTimestamps) {
  params_ = vk::Buffer(ctx, sizeof(gpu::FrameParams), vk::kStorageUsage, vk::MemoryUse::Upload,
                       "frame params");
  stats_ = vk::Buffer(ctx, sizeof(gpu::RenderStats), vk::kStorageUsage, vk::MemoryUse::Readback,
                      "render stats");
}

void FrameResources::setTransferFunction(const scene::TransferFunction& world, double scale,
                                         bool preintegrated) {
  const std::vector<glm::vec4> table = deviceTable(world);
  ensure(ctx_, transferFunction_, table.size() * sizeof(glm::vec4), "transfer function");
  transferFunction_.upload(table.data(), table.size() * sizeof(glm::vec4));
  if (!preintegrated) return;
  scene::TransferFunction tf = world;  // extinction per device unit
  tf.unitDistance *= scale;
  Hasher h;
  h.span(std::span<const glm::vec4>(tf.table))
      .pod(tf.lo)
      .pod(tf.hi)
      .pod(tf.scale)
      .pod(tf.opacityScale)
      .pod(tf.unitDistance);
  const uint64_t key = h.digest();
  if (preintegration_.valid() && key == preintegrationKey_) return;
  preintegrationTable_ = buildPreintegration(tf);
  const std::vector<uint64_t> words = preintegrationTable_.deviceWords();
  const size_t bytes = words.size() * sizeof(uint64_t);
  ensure(ctx_, preintegration_, bytes, "pre-integrated transfer function");
  preintegration_.upload(words.data(), bytes);
  preintegrationKey_ = key;
}

VkDeviceAddress FrameResources::transferFunction() const {
  return transferFunction_.valid() ? transferFunction_.address() : 0;
}

void FrameResources::resetStats() {
  const gpu::RenderStats zero{};
  stats_.upload(&zero, sizeof zero);
}

gpu::RenderStats FrameResources::readStats() const {
  gpu::RenderStats s;
  stats_.download(&s, sizeof s);
  return s;
}

void FrameResources::setRays(const std::vector<gpu::RayDesc>& rays) {
  const uint64_t bytes = rays.size() * sizeof(gpu::RayDesc);
  ensure(ctx_, rays_, bytes, "rays");
  rays_.upload(rays.data(), bytes);
}

VkDeviceAddress FrameResources::segments(uint64_t count) {
  const uint64_t bytes = std::max<uint64_t>(count, 1) * sizeof(gpu::Segment);
  if (!segments_.valid() || segments_.size() < bytes)  // a quarter more: frames vary a little
    segments_ =
        vk::Buffer(ctx_, bytes + bytes / 4, vk::kStorageUsage, vk::MemoryUse::Device, "segments");
  return segments_.address();
}

void FrameResources::noteSegments(uint64_t total, bool kept) {
  lastSegmentTotal_ = total;
  lastSegmentsKept_ = kept;
}

std::vector<gpu::Segment> FrameResources::lastSegments() const {
  SM_CHECK(lastSegmentsKept());
  std::vector<gpu::Segment> all(lastSegmentTotal_);
  segments_.download(all.data(), all.size() * sizeof(gpu::Segment));
  return all;
}

bool FrameResources::ensureSegmentCache(uint64_t bytes) {
  if (segmentCache_.valid() && segmentCache_.size() >= bytes) return true;
  if (failedCacheBytes_ != 0 && bytes >= failedCacheBytes_) return false;  // tried: no room
  segmentCache_ = vk::Buffer();
  try {
    segmentCache_ =
        vk::Buffer(ctx_, bytes, vk::kStorageUsage, vk::MemoryUse::Device, "segment cache");
    return true;
  } catch (const vk::DeviceMemoryError&) {
    failedCacheBytes_ = bytes;
    return false;
  }
}

std::vector<double> FrameResources::timedSubmit(
    const std::function<void(VkCommandBuffer, const Mark&)>& record) {
  uint32_t written = 0;
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    // A fence wait makes earlier submissions' writes visible to the host only: the scan's offsets
    // and the parameters rewritten since need this barrier to reach these shaders.
    comp::previousWorkBarrier(cmd);
    timestamps_.reset(cmd);
    timestamps_.write(cmd, written++);
    record(cmd, [&] {
      SM_CHECK(written + 1 < kTimestamps);
      timestamps_.write(cmd, written++);
    });
    timestamps_.write(cmd, written++);
  });
  const std::vector<uint64_t> ts = timestamps_.results(written);
  std::vector<double> ms;
  for (uint32_t i = 0; i + 1 < written; ++i) ms.push_back(timestamps_.ms(ts, i, i + 1));
  return ms;
}

double FrameResources::timedSubmit(const std::function<void(VkCommandBuffer)>& record) {
  return timedSubmit([&](VkCommandBuffer cmd, const Mark&) { record(cmd); }).front();
}

}  // namespace sm::render
