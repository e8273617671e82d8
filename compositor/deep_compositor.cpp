#include "compositor/deep_compositor.h"

#include <chrono>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "comm/communicator.h"
#include "compositor/deep_exchange.h"
#include "compositor/device_util.h"
#include "compositor/exchange_plan.h"
#include "compositor_shaders.h"
#include "exchange_types.h"

namespace sm::comp {
namespace {
static_assert(std::is_trivially_copyable_v<CompositeStats>);
}  // namespace

uint32_t fragmentBytes(Encoding e) {
  return e == Encoding::Float ? sizeof(DcFragment) : sizeof(DcPackedFragment);
}

DeepCompositor::DeepCompositor(const vk::Context& ctx, comm::Communicator* comm, int width,
                               int height, CompositorOptions options)
    : ctx_(ctx),
      comm_(comm),
      width_(width),
      height_(height),
      options_(options),
      scan_(ctx),
      listStats_(ctx) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("compositor: empty image " + std::to_string(width) + "x" +
                                std::to_string(height));
  if (uint64_t(width) * uint64_t(height) > 0xffffffffull)
    throw std::invalid_argument("compositor: more than 2^32 - 1 pixels");
  if (options_.mode != ListMode::TwoPass && options_.fixedK == 0)
    throw std::invalid_argument("compositor: fixed-length lists need K >= 1");
  // Shaders index the slots (pixel * K) with 32-bit integers, which SPIR-V may read as signed.
  if (options_.mode != ListMode::TwoPass &&
      uint64_t(width) * uint64_t(height) * options_.fixedK > uint64_t(kMaxListIndex))
    throw std::invalid_argument("compositor: fixed-length lists of " +
                                std::to_string(options_.fixedK) + " slots over " +
                                std::to_string(width) + "x" + std::to_string(height) +
                                " pixels are more than " + std::to_string(kMaxListIndex) +
                                " slots (--k): use a smaller --k or image, or two-pass lists");
  chooseCounterBits(0, options_.counterBits);  // rejects widths that are no encoding
  const uint64_t pixels = uint64_t(width) * height;
  const auto device = vk::MemoryUse::Device;
  growBuffer(capacities_, ctx, pixels * 4, device, "list capacities", allocations_);
  growBuffer(offsets_, ctx, pixels * 4, device, "list offsets", allocations_);
  growBuffer(counts_, ctx, pixels * 4, device, "list counts", allocations_);
  if (options_.mode != ListMode::TwoPass) growFragments(pixels * options_.fixedK);
  const std::vector<vk::SpecConstant> spec = {{100, modeConstant()}, {101, encodingConstant()}};
  compositeLocal_ = vk::ComputePipeline(
      ctx, {"composite_local", spv::composite_local(), spec, sizeof(DcLocalPush), false});
  if (ranks() > 1)
    exchange_ = std::make_unique<DeepExchange>(ctx, *comm, uint32_t(pixels), options_, scan_,
                                               listStats_, allocations_);
  else
    growBuffer(image_, ctx, pixels * sizeof(glm::vec4), vk::MemoryUse::Readback, "composited image",
               allocations_);
}

DeepCompositor::~DeepCompositor() = default;

int DeepCompositor::rank() const {
  return comm_ ? comm_->rank() : 0;
}
int DeepCompositor::ranks() const {
  return comm_ ? comm_->size() : 1;
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
  growBuffer(fragments_, ctx_, std::max<uint64_t>(count, 1) * fragmentBytes(options_.encoding),
             vk::MemoryUse::Device, "fragments", allocations_);
}

uint64_t DeepCompositor::prepareLists() {
  if (options_.mode != ListMode::TwoPass)
    throw std::logic_error("compositor: prepareLists() is for two-pass lists only");
  const uint32_t pixels = uint32_t(width_) * uint32_t(height_);
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    previousWorkBarrier(cmd);
    copyBuffer(cmd, capacities_, 0, offsets_, 0, uint64_t(pixels) * 4);
    vk::transferToComputeBarrier(cmd);
    scan_.record(cmd, offsets_.address(), pixels);
    hostReadBarrier(cmd);
  });
  const uint32_t total = scan_.downloadTotal("the pixels' list lengths");
  growFragments(total);
  return total;
}

ListsView DeepCompositor::renderLists() const {
  if (!fragments_.valid())
    throw std::logic_error("compositor: composite() before prepareLists() on two-pass lists");
  const bool twoPass = options_.mode == ListMode::TwoPass;
  return {&fragments_, &counts_, twoPass ? &offsets_ : nullptr, twoPass ? 0u : options_.fixedK};
}

// Single-fragment compositing, first half: one fragment per pixel and rank.
ListsView DeepCompositor::flatten(const ListsView& lists) {
  const uint32_t pixels = uint32_t(width_) * uint32_t(height_);
  if (!flatten_.valid())
    flatten_ = vk::ComputePipeline(
        ctx_,
        {"flatten", spv::flatten(), {{101, encodingConstant()}}, sizeof(DcCompactPush), false});
  growBuffer(flatFragments_, ctx_, uint64_t(pixels) * fragmentBytes(options_.encoding),
             vk::MemoryUse::Device, "flattened fragments", allocations_);
  growBuffer(flatCounts_, ctx_, uint64_t(pixels) * 4, vk::MemoryUse::Device, "flattened counts",
             allocations_);
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    previousWorkBarrier(cmd);
    DcCompactPush p{lists.fragments->address(),
                    lists.counts->address(),
                    lists.offsets ? lists.offsets->address() : 0,
                    flatFragments_.address(),
                    0,
                    flatCounts_.address(),
                    pixels,
                    lists.fixedK,
                    0,
                    0,
                    {},
                    0,
                    0};
    flatten_.dispatchItems(cmd, pixels, 64, p);
  });
  return {&flatFragments_, &flatCounts_, nullptr, 1};
}

void DeepCompositor::compositeLocal(const ListsView& lists, std::vector<glm::vec4>& image) {
  const uint32_t pixels = uint32_t(width_) * uint32_t(height_);
  DcLocalPush push{lists.fragments->address(),
                   lists.counts->address(),
                   lists.offsets ? lists.offsets->address() : 0,
                   image_.address(),
                   pixels,
                   lists.fixedK};
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    previousWorkBarrier(cmd);
    listStats_.record(cmd, lists.counts->address(), pixels);
    compositeLocal_.dispatchItems(cmd, pixels, 64, push);
    hostReadBarrier(cmd);
  });
  image.resize(pixels);
  image_.download(image.data(), uint64_t(pixels) * sizeof(glm::vec4));
  ListTotals t = listStats_.read();
  stats_.fragments = t.fragments;
  stats_.nonEmptyPixels = t.nonEmptyPixels;
  stats_.longestList = t.longest;
  stats_.fragmentsComposited = t.fragments;
}

std::vector<glm::vec4> DeepCompositor::composite(CompositeMethod method) {
  std::vector<glm::vec4> out;
  composite(method, out);
  return out;
}

void DeepCompositor::composite(CompositeMethod method, std::vector<glm::vec4>& image) {
  auto start = std::chrono::steady_clock::now();
  stats_ = {};
  ListsView lists = renderLists();
  if (method == CompositeMethod::SingleFragment) lists = flatten(lists);
  if (exchange_) {
    exchange_->run(lists, image, stats_);
    if (rank() != 0) image.clear();
  } else {
    compositeLocal(lists, image);
  }
  stats_.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (!exchange_) stats_.timings.composite = stats_.milliseconds;
}

std::vector<CompositeStats> DeepCompositor::gatherStats() {
  if (ranks() == 1) return {stats_};
  std::vector<CompositeStats> all;
  std::vector<uint64_t> bytes, offsets;
  if (rank() == 0) {
    all.resize(size_t(ranks()));
    for (int r = 0; r < ranks(); ++r) {
      bytes.push_back(sizeof(CompositeStats));
      offsets.push_back(uint64_t(r) * sizeof(CompositeStats));
    }
  }
  comm_->gatherv(&stats_, sizeof stats_, all.data(), bytes, offsets, 0);
  return all;
}

std::vector<std::vector<uint32_t>> DeepCompositor::gatherCounts() {
  std::vector<uint32_t> mine;
  downloadCounts(mine);
  if (ranks() == 1) return {mine};
  const uint64_t bytes = mine.size() * 4;
  std::vector<uint32_t> all;
  std::vector<uint64_t> sizes, offsets;
  if (rank() == 0) {
    all.resize(mine.size() * size_t(ranks()));
    for (int r = 0; r < ranks(); ++r) {
      sizes.push_back(bytes);
      offsets.push_back(uint64_t(r) * bytes);
    }
  }
  comm_->gatherv(mine.data(), bytes, all.data(), sizes, offsets, 0);
  std::vector<std::vector<uint32_t>> out;
  for (int r = 0; rank() == 0 && r < ranks(); ++r)
    out.emplace_back(all.begin() + r * mine.size(), all.begin() + (r + 1) * mine.size());
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
