// Deep compositing (the paper's section "Deep Compositing"): every rank writes a variable-length
// list of fragments per pixel through the device interface (shaders/fragment_list.glsl); the
// compositor exchanges the lists so that each rank owns a share of the pixels (interleaved by
// default, CompositorOptions::ownership), composites each pixel's
// fragments from all ranks in visibility order, and gathers the image on rank 0.
//
// Host use per frame:
//   two-pass lists: renderer counts into capacities(), then prepareLists() (prefix sum, storage
//   grows to the total), renderer writes fragments at lists().offsets, then composite();
//   fixed-length lists: renderer writes K slots per pixel, then composite().
// composite() is collective: every rank calls it once per frame. One rank (no communicator, or a
// communicator of size 1) composites locally with no exchange at all.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec4.hpp>

#include "compositor/exchange_plan.h"
#include "compositor/list_statistics.h"
#include "compositor/prefix_sum.h"
#include "fragment_types.h"
#include "vk/buffer.h"
#include "vk/pipeline.h"

namespace sm::comm {
class Communicator;
}

namespace sm::comp {

class DeepExchange;
struct ListsView;

enum class ListMode { TwoPass, FixedDrop, FixedMerge };
enum class Encoding { Float, Rgba8 };
// Deep: every fragment in visibility order (correct). SingleFragment: each rank first composites
// its own list into one fragment at its first depth, then ranks are blended by depth (IceT-like,
// wrong for interleaved partitions; for comparison).
enum class CompositeMethod { Deep, SingleFragment };

struct CompositorOptions {
  ListMode mode = ListMode::TwoPass;
  Encoding encoding = Encoding::Float;
  uint32_t fixedK = 8;       // slots per pixel for fixed-length lists
  uint32_t counterBits = 0;  // 0: 2, 4, 8 or 32 from the longest list; else forced (must fit)
  uint32_t registerLists =
      8;  // non-empty lists per pixel merged in registers; more merge in memory
  // Which rank composites which pixels (exchange_plan.h). Interleaved balances the compositing
  // work whatever part of the image the data covers; Ranges is the paper's layout.
  PixelOwnership ownership = PixelOwnership::Interleaved;
  bool operator==(const CompositorOptions&) const = default;
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

// Host wall-clock time of each step on this rank (milliseconds).
struct CompositeTimings {
  double prepare = 0;           // step 1: statistics, prefix sum, compaction, count encoding
  double countExchange = 0;     // step 2 and the prefix sum over received counts
  double fragmentExchange = 0;  // step 3
  double composite = 0;         // step 4 (one rank: the whole local compositing)
  double gather = 0;            // step 5
};

// One rank's statistics of the last frame; they describe the lists that were composited (for
// SingleFragment: the flattened ones). Plain data, so that gatherStats() can move it as bytes.
struct CompositeStats {
  uint64_t fragments = 0;          // this rank's fragments
  uint64_t nonEmptyPixels = 0;     // pixels with at least one fragment on this rank
  uint32_t longestList = 0;        // on this rank
  uint32_t counterBits = 0;        // bits per counter in the count exchange (0: no exchange)
  uint64_t countBytesSent = 0;     // to other ranks, headers included (not the share a rank keeps)
  uint64_t fragmentBytesSent = 0;  // to other ranks
  uint64_t bytesSent = 0;          // counts + fragments
  uint64_t fragmentsComposited = 0;  // fragments of the pixels this rank owns, from all ranks
  double milliseconds = 0;           // all of composite() on this rank
  CompositeTimings timings;
  double fragmentsPerNonEmptyPixel() const {
    return nonEmptyPixels ? double(fragments) / double(nonEmptyPixels) : 0.0;
  }
};

class DeepCompositor {
 public:
  // comm == nullptr: one rank, no exchange. The communicator must outlive the compositor.
  DeepCompositor(const vk::Context& ctx, comm::Communicator* comm, int width, int height,
                 CompositorOptions options);
  ~DeepCompositor();

  const vk::Context& context() const { return ctx_; }
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
  // Composites all ranks' lists (collective); returns premultiplied RGBA on rank 0 (row 0 at the
  // top), empty on other ranks.
  std::vector<glm::vec4> composite(CompositeMethod method = CompositeMethod::Deep);
  // The same into a caller's vector (no host allocation once it is large enough).
  void composite(CompositeMethod method, std::vector<glm::vec4>& image);
  const CompositeStats& stats() const { return stats_; }
  // Collective: every rank's stats of the last frame, on rank 0 (empty elsewhere).
  std::vector<CompositeStats> gatherStats();
  // Collective: every rank's per-pixel fragment counts of the last frame (the paper's heatmaps),
  // on rank 0 (empty elsewhere).
  std::vector<std::vector<uint32_t>> gatherCounts();
  // Per-pixel list capacities (two-pass) and fragment counts of the last frame, for statistics.
  void downloadCapacities(std::vector<uint32_t>& out) const;
  void downloadCounts(std::vector<uint32_t>& out) const;
  // This rank's lists of the last frame, per pixel in list order, decoded to floats (tests).
  std::vector<std::vector<DcFragment>> downloadLists() const;
  // Device buffers (re)allocated so far: steady frames of similar size allocate nothing.
  uint64_t allocations() const { return allocations_; }

 private:
  void growFragments(uint64_t count);
  ListsView renderLists() const;
  ListsView flatten(const ListsView& lists);
  void compositeLocal(const ListsView& lists, std::vector<glm::vec4>& image);
  const vk::Context& ctx_;
  comm::Communicator* comm_;
  int width_, height_;
  CompositorOptions options_;
  uint64_t allocations_ = 0;
  PrefixSum scan_;
  ListStatistics listStats_;
  vk::Buffer capacities_, offsets_, counts_, fragments_, image_;
  vk::Buffer flatFragments_, flatCounts_;  // SingleFragment: one fragment per pixel
  vk::ComputePipeline compositeLocal_, flatten_;
  std::unique_ptr<DeepExchange> exchange_;
  CompositeStats stats_;
};

}  // namespace sm::comp
