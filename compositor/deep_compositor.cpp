#include "compositor/deep_compositor.h"

#include <chrono>
#include <cstring>
#include <stdexcept>

#include "compositor_shaders.h"

namespace sm::comp {
namespace {
struct LocalPush {
  uint64_t fragments, counts, offsets, image;
  uint32_t pixels, fixedK;
};
}  // namespace

uint32_t fragmentBytes(Encoding e) {
  return e == Encoding::Float ? sizeof(DcFragment) : sizeof(DcPackedFragment);
}

DeepCompositor::DeepCompositor(const vk::Context& ctx, Communicator* comm, int width, int height,
                               CompositorOptions options)
    : ctx_(ctx), comm_(comm), width_(width), height_(height), options_(options), scan_(ctx) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("compositor: empty image");
  if (options_.mode != ListMode::TwoPass && options_.fixedK == 0)
    throw std::invalid_argument("compositor: fixed-length lists need K >= 1");
  const uint64_t pixels = uint64_t(width) * height;
  const VkBufferUsageFlags usage = vk::kStorageUsage;
  capacities_ = vk::Buffer(ctx, pixels * 4, usage, vk::MemoryUse::Device, "list capacities");
  offsets_ = vk::Buffer(ctx, pixels * 4, usage, vk::MemoryUse::Device, "list offsets");
  counts_ = vk::Buffer(ctx, pixels * 4, usage, vk::MemoryUse::Device, "list counts");
  image_ = vk::Buffer(ctx, pixels * sizeof(glm::vec4), usage, vk::MemoryUse::Readback,
                      "composited image");
  if (options_.mode != ListMode::TwoPass) growFragments(pixels * options_.fixedK);
  compositeLocal_ = vk::ComputePipeline(ctx, {"composite_local",
                                              spv::composite_local(),
                                              {{100, modeConstant()}, {101, encodingConstant()}},
                                              sizeof(LocalPush),
                                              false});
}

DeepCompositor::~DeepCompositor() = default;

int DeepCompositor::rank() const {
  return 0;
}
int DeepCompositor::ranks() const {
  return 1;
}

uint32_t DeepCompositor::modeConstant() const {
  switch (options_.mode) {
    case ListMode::TwoPass:
      return DC_TWO_PASS;
    case ListMode::FixedDrop:
      return DC_FIXED_DROP;
    case ListMode::FixedMerge:
      return DC_FIXED_MERGE;
  }
  return DC_TWO_PASS;
}

uint32_t DeepCompositor::encodingConstant() const {
  return options_.encoding == Encoding::Float ? DC_ENCODING_FLOAT : DC_ENCODING_RGBA8;
}

DeviceLists DeepCompositor::lists() const {
  DeviceLists l;
  l.capacities = capacities_.address();
  l.offsets = offsets_.address();
  l.counts = counts_.address();
  l.fragments = fragments_.valid() ? fragments_.address() : 0;
  l.fixedK = options_.mode == ListMode::TwoPass ? 0 : options_.fixedK;
  return l;
}

void DeepCompositor::growFragments(uint64_t count) {
  uint64_t bytes = std::max<uint64_t>(count, 1) * fragmentBytes(options_.encoding);
  if (fragments_.valid() && fragments_.size() >= bytes) return;
  // Grow with headroom so that frames with slowly rising fragment counts do not reallocate.
  fragments_ =
      vk::Buffer(ctx_, bytes + bytes / 4, vk::kStorageUsage, vk::MemoryUse::Device, "fragments");
}

uint64_t DeepCompositor::prepareLists() {
  const uint32_t pixels = uint32_t(width_) * uint32_t(height_);
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    VkBufferCopy copy{0, 0, uint64_t(pixels) * 4};
    vkCmdCopyBuffer(cmd, capacities_.handle(), offsets_.handle(), 1, &copy);
    vk::transferToComputeBarrier(cmd);
    scan_.record(cmd, offsets_.address(), pixels);
  });
  uint32_t total = 0;
  scan_.total().download(&total, sizeof total);
  growFragments(total);
  return total;
}

std::vector<glm::vec4> DeepCompositor::composite() {
  auto start = std::chrono::steady_clock::now();
  const uint32_t pixels = uint32_t(width_) * uint32_t(height_);
  LocalPush push{fragments_.address(),
                 counts_.address(),
                 options_.mode == ListMode::TwoPass ? offsets_.address() : 0,
                 image_.address(),
                 pixels,
                 options_.fixedK};
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    compositeLocal_.dispatch(cmd, vk::groupsFor(pixels, 64), 1, 1, push);
  });
  std::vector<glm::vec4> out(pixels);
  image_.download(out.data(), uint64_t(pixels) * sizeof(glm::vec4));
  stats_.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  stats_.bytesSent = 0;
  return out;
}

void DeepCompositor::downloadCapacities(std::vector<uint32_t>& out) const {
  out.resize(uint64_t(width_) * height_);
  capacities_.download(out.data(), out.size() * 4);
}

void DeepCompositor::downloadCounts(std::vector<uint32_t>& out) const {
  out.resize(uint64_t(width_) * height_);
  counts_.download(out.data(), out.size() * 4);
}

std::vector<std::vector<DcFragment>> DeepCompositor::downloadLists() const {
  std::vector<uint32_t> counts, offsets(uint64_t(width_) * height_);
  downloadCounts(counts);
  if (options_.mode == ListMode::TwoPass) {
    offsets_.download(offsets.data(), offsets.size() * 4);
  } else {
    for (size_t p = 0; p < offsets.size(); ++p) offsets[p] = uint32_t(p * options_.fixedK);
  }
  std::vector<std::vector<DcFragment>> out(counts.size());
  if (!fragments_.valid()) return out;
  const uint32_t bytes = fragmentBytes(options_.encoding);
  std::vector<uint8_t> raw(fragments_.size());
  fragments_.download(raw.data(), raw.size());
  for (size_t p = 0; p < counts.size(); ++p) {
    for (uint32_t i = 0; i < counts[p]; ++i) {
      const uint8_t* at = raw.data() + uint64_t(offsets[p] + i) * bytes;
      DcFragment f;
      if (options_.encoding == Encoding::Float) {
        std::memcpy(&f, at, sizeof f);
      } else {
        DcPackedFragment q;
        std::memcpy(&q, at, sizeof q);
        for (int c = 0; c < 4; ++c) f.color[c] = float((q.rgba8 >> (8 * c)) & 0xFF) / 255.0f;
        f.depth = q.depth;
      }
      out[p].push_back(f);
    }
  }
  return out;
}

}  // namespace sm::comp
