// Deep compositing (the paper's section "Deep Compositing"): every rank writes a variable-length
// list of fragments per pixel through the device interface (shaders/fragment_list.glsl); the
// compositor exchanges the lists so that each rank owns a range of pixels, composites each pixel's
// fragments from all ranks in visibility order, and gathers the image on rank 0.
//
// Host use per frame:
//   two-pass lists: renderer counts into capacities(), then prepareLists() (prefix sum, storage
//   grows to the total), renderer writes fragments at lists().offsets, then composite();
//   fixed-length lists: renderer writes K slots per pixel, then composite().
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec4.hpp>

#include "compositor/prefix_sum.h"
#include "fragment_types.h"
#include "vk/buffer.h"
#include "vk/pipeline.h"

namespace sm::comp {

class Communicator;

enum class ListMode { TwoPass, FixedDrop, FixedMerge };
enum class Encoding { Float, Rgba8 };

struct CompositorOptions {
  ListMode mode = ListMode::TwoPass;
  Encoding encoding = Encoding::Float;
  uint32_t fixedK = 8;  // slots per pixel for fixed-length lists
};

uint32_t fragmentBytes(Encoding e);

// Device addresses a renderer's fragment-writing shader needs.
struct DeviceLists {
  VkDeviceAddress capacities = 0;  // two-pass: per-pixel upper bound written by the counting pass
  VkDeviceAddress offsets = 0;     // two-pass: list start per pixel (prefix sum of capacities)
  VkDeviceAddress counts = 0;      // fragments written per pixel
  VkDeviceAddress fragments = 0;
  uint32_t fixedK = 0;
};

struct CompositeStats {
  uint64_t fragments = 0;   // this rank's fragments this frame
  uint64_t bytesSent = 0;   // to other ranks (counts + fragments), this frame
  double milliseconds = 0;  // compositing time on this rank
};

class DeepCompositor {
 public:
  // comm == nullptr: one rank, no exchange.
  DeepCompositor(const vk::Context& ctx, Communicator* comm, int width, int height,
                 CompositorOptions options);
  ~DeepCompositor();

  int width() const { return width_; }
  int height() const { return height_; }
  const CompositorOptions& options() const { return options_; }
  int rank() const;
  int ranks() const;
  // Specialization constants (ids 100, 101) for pipelines that include fragment_list.glsl.
  uint32_t modeConstant() const;
  uint32_t encodingConstant() const;

  DeviceLists lists() const;
  // Two-pass only: scans capacities into offsets and grows storage; returns the total.
  uint64_t prepareLists();
  // Composites all ranks' lists; returns premultiplied RGBA on rank 0 (row 0 at the top), empty on
  // other ranks.
  std::vector<glm::vec4> composite();
  const CompositeStats& stats() const { return stats_; }
  // Per-pixel list capacities (two-pass) and fragment counts of the last frame, for statistics.
  void downloadCapacities(std::vector<uint32_t>& out) const;
  void downloadCounts(std::vector<uint32_t>& out) const;
  // This rank's lists of the last frame, per pixel in list order, decoded to floats (tests).
  std::vector<std::vector<DcFragment>> downloadLists() const;

 private:
  void growFragments(uint64_t count);
  const vk::Context& ctx_;
  Communicator* comm_;
  int width_, height_;
  CompositorOptions options_;
  PrefixSum scan_;
  vk::Buffer capacities_, offsets_, counts_, fragments_, image_;
  vk::ComputePipeline compositeLocal_;
  CompositeStats stats_;
};

}  // namespace sm::comp
