// Shell acceleration structures: one triangle BLAS over a rank's shell and a TLAS holding it.
#pragma once

#include <cstdint>

#include "vk/buffer.h"

namespace sm::vk {

class AccelerationStructure {
 public:
  AccelerationStructure() = default;
  AccelerationStructure(AccelerationStructure&&) noexcept = default;
  AccelerationStructure& operator=(AccelerationStructure&&) noexcept = default;

  VkAccelerationStructureKHR handle() const { return as_.get(); }
  VkDeviceAddress address() const { return address_; }
  VkDeviceSize bytes() const { return storage_.size(); }
  bool valid() const { return bool(as_); }

  // BLAS over triangles: positions (float xyz, `vertexCount`), indices (3 x uint32 per triangle).
  // Opaque geometry, built for fast trace, compacted when `compact` and it saves memory.
  static AccelerationStructure buildTriangles(const Context& ctx, const Buffer& positions,
                                              uint32_t vertexCount, const Buffer& indices,
                                              uint32_t triangleCount, bool compact,
                                              const std::string& name);
  // BLAS over axis-aligned boxes (VkAabbPositionsKHR, `count` of them): procedural primitives whose
  // intersections the shader decides. Not opaque, so every candidate reaches the shader.
  static AccelerationStructure buildBoxes(const Context& ctx, const Buffer& aabbs, uint32_t count,
                                          bool compact, const std::string& name);
  // TLAS with one identity instance of `blas`, or with no instance at all (blas == nullptr), so
  // that a rank with no elements runs the same shaders and simply finds nothing.
  static AccelerationStructure buildInstance(const Context& ctx, const AccelerationStructure* blas,
                                             const std::string& name);

  // Bytes a bottom-level build needs at its peak (structure plus scratch) as the device reports
  // them, allocating nothing: over `count` boxes, or over `count` triangles of `vertexCount`
  // vertices. Out-of-memory messages compare it with what the device has.
  static VkDeviceSize bottomLevelBuildBytes(const Context& ctx, bool boxes, uint32_t count,
                                            uint32_t vertexCount);

  // An empty structure of the given type and size, with its storage (used by the builders).
  static AccelerationStructure create(const Context& ctx, VkAccelerationStructureTypeKHR type,
                                      VkDeviceSize size, const std::string& name);

 private:
  Buffer storage_;
  DeviceHandle<VkAccelerationStructureKHR> as_;
  VkDeviceAddress address_ = 0;
};

}  // namespace sm::vk
