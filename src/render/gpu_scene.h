// One rank's prepared data on the device: buffers reached by address and the shell's acceleration
// structures. Changing the field or time step uploads scalars only (no rebuild).
#pragma once

#include <atomic>
#include <cstdint>
#include <span>
#include <vector>

#include "prep/memory_report.h"
#include "prep/prepared_rank.h"
#include "shared/render_types.h"
#include "vk/accel.h"
#include "vk/buffer.h"

namespace sm::render {

// Padded boxes of the shell triangles (ShellGeometry::Boxes). The padding keeps rays that run
// exactly along a triangle's plane or edge from being missed by the device's float box test; the
// exact test then decides. It scales with the shell alone: points no element uses, however far,
// leave the boxes tight.
std::vector<VkAabbPositionsKHR> shellBoxes(const prep::PreparedRank& r,
                                           std::span<const float> positions);

// How the shell BLAS holds the shell. Boxes: one padded box per shell triangle, every candidate
// decided by the exact crossing predicates the marcher uses (exact everywhere, the default).
// Triangles: the device's own triangle test decides (faster where RT cores test triangles, but a
// ray through a shell vertex or edge may be judged differently from the marcher).
enum class ShellGeometry { Boxes, Triangles };

class GpuScene {
 public:
  // `positions`: the rank's (rank.positions, which the rest of `rank` indexes). The scene keeps
  // them on the host to interleave each time step's scalars with: callers with no further use for
  // them move them in (`GpuScene(ctx, rank, std::move(rank.positions))`), so that the host holds
  // one copy, not two.
  GpuScene(const vk::Context& ctx, const prep::PreparedRank& rank, std::vector<float> positions,
           ShellGeometry shell = ShellGeometry::Boxes);
  // Device memory a scene of `rank` needs while it is built (buffers, shell boxes, BLAS with its
  // build scratch), allocating nothing: what an out-of-memory message compares with the device.
  static uint64_t requiredBytes(const vk::Context& ctx, const prep::PreparedRank& rank,
                                ShellGeometry shell = ShellGeometry::Boxes);
  ShellGeometry shellGeometry() const { return shell_; }

  // Scalars in this rank's vertex order (prep::gatherScalars); size must equal the vertex count.
  // Writes the buffer frames read: not while one renders.
  void setScalars(const std::vector<float>& values);
  // Double buffering for sequences. stageScalars writes a second buffer (allocated on first use)
  // that frames do not read, so it may run on another thread while a frame renders; swapScalars,
  // between frames and after stageScalars returned, makes it the one frames read. Neither may run
  // alongside setScalars, deviceBytes or the other.
  void stageScalars(std::span<const float> values);
  void swapScalars();
  // How many times geometry/acceleration structures were built (1 for the scene's life).
  uint64_t geometryBuilds() const { return geometryBuilds_; }
  uint64_t scalarUploads() const { return scalarUploads_; }

  gpu::SceneRefs refs() const;
  bool empty() const { return shellTriangles_ == 0; }
  bool compact() const { return compact_; }
  uint32_t typesPresent() const { return typesPresent_; }
  uint64_t numVertices() const { return numVertices_; }
  uint64_t shellTriangles() const { return shellTriangles_; }
  VkAccelerationStructureKHR tlas() const { return tlas_.handle(); }
  uint64_t accelerationStructureBytes() const { return blas_.bytes() + tlas_.bytes(); }
  uint64_t deviceBytes() const;  // every buffer this scene holds
  // Device coordinates of a world point: rebased on the frame's origin and scaled by its power of
  // two (prep::GlobalFrame); lengths along rays scale by scale().
  glm::dvec3 toDevice(const glm::dvec3& world) const { return (world - origin_) * scale_; }
  double scale() const { return scale_; }
  // Bounds of this rank's vertices in device coordinates (empty for a rank with no elements).
  const mesh::Bounds& rebasedBounds() const { return bounds_; }

 private:
  const vk::Context& ctx_;
  ShellGeometry shell_;
  bool compact_;
  uint32_t typesPresent_;
  uint64_t numVertices_, shellTriangles_;
  glm::dvec3 origin_;
  double scale_;
  mesh::Bounds bounds_;
  void uploadVertices(vk::Buffer& buffer, std::span<const float> scalars) const;

  std::vector<float> positions_;  // xyz per vertex, to interleave each step's scalars with
  vk::Buffer shellIndices_, shellRefs_, shellOther_, shellAdjacency_;
  vk::Buffer vertices_[2];  // xyz + scalar per vertex; frames read vertices_[front_]
  int front_ = 0;
  vk::Buffer elements_[4], neighbors_[4];
  vk::AccelerationStructure blas_, tlas_;
  uint64_t geometryBuilds_ = 0;
  std::atomic<uint64_t> scalarUploads_{0};
};

}  // namespace sm::render
