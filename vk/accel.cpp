#include "vk/accel.h"

#include "vk/vk_error.h"

namespace sm::vk {

AccelerationStructure AccelerationStructure::create(const Context& ctx,
                                                    VkAccelerationStructureTypeKHR type,
                                                    VkDeviceSize size, const std::string& name) {
  AccelerationStructure a;
  a.storage_ = Buffer(ctx, size, VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR,
                      MemoryUse::Device, name + " storage");
  VkAccelerationStructureCreateInfoKHR ci{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
  ci.buffer = a.storage_.handle();
  ci.size = size;
  ci.type = type;
  VkAccelerationStructureKHR as;
  SM_VK(ctx.fn().createAccelerationStructure(ctx.device(), &ci, nullptr, &as));
  a.as_ = DeviceHandle<VkAccelerationStructureKHR>(ctx.device(), as,
                                                   ctx.fn().destroyAccelerationStructure);
  ctx.setName(VK_OBJECT_TYPE_ACCELERATION_STRUCTURE_KHR, uint64_t(as), name);
  VkAccelerationStructureDeviceAddressInfoKHR ai{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
  ai.accelerationStructure = as;
  a.address_ = ctx.fn().getAccelerationStructureDeviceAddress(ctx.device(), &ai);
  return a;
}

namespace {

void buildBarrier(VkCommandBuffer cmd) {
  memoryBarrier(cmd, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR,
                VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR |
                    VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR);
}

// Builds a BLAS over one geometry and compacts it when asked and worthwhile.
AccelerationStructure buildBottomLevel(
    const Context& ctx, const VkAccelerationStructureGeometryKHR& geom, uint32_t primitiveCount,
    bool compact, const std::string& name,
    AccelerationStructure (*create)(const Context&, VkAccelerationStructureTypeKHR, VkDeviceSize,
                                    const std::string&)) {
  VkAccelerationStructureBuildGeometryInfoKHR build{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  build.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
  build.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR |
                (compact ? VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_COMPACTION_BIT_KHR : 0);
  build.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  build.geometryCount = 1;
  build.pGeometries = &geom;
  VkAccelerationStructureBuildSizesInfoKHR sizes{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  ctx.fn().getAccelerationStructureBuildSizes(ctx.device(),
                                              VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR,
                                              &build, &primitiveCount, &sizes);
  AccelerationStructure blas = create(ctx, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR,
                                      sizes.accelerationStructureSize, name);
  Buffer scratch(ctx, sizes.buildScratchSize, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::Device,
                 name + " scratch");
  build.dstAccelerationStructure = blas.handle();
  build.scratchData.deviceAddress = scratch.address();
  VkAccelerationStructureBuildRangeInfoKHR range{primitiveCount, 0, 0, 0};
  const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
  DeviceHandle<VkQueryPool> query;
  if (compact) {
    VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qci.queryType = VK_QUERY_TYPE_ACCELERATION_STRUCTURE_COMPACTED_SIZE_KHR;
    qci.queryCount = 1;
    VkQueryPool pool;
    SM_VK(vkCreateQueryPool(ctx.device(), &qci, nullptr, &pool));
    query = DeviceHandle<VkQueryPool>(ctx.device(), pool, vkDestroyQueryPool);
  }
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    ctx.fn().cmdBuildAccelerationStructures(cmd, 1, &build, &ranges);
    if (compact) {
      buildBarrier(cmd);
      vkCmdResetQueryPool(cmd, query.get(), 0, 1);
      VkAccelerationStructureKHR h = blas.handle();
      ctx.fn().cmdWriteAccelerationStructuresProperties(
          cmd, 1, &h, VK_QUERY_TYPE_ACCELERATION_STRUCTURE_COMPACTED_SIZE_KHR, query.get(), 0);
    }
  });
  if (!compact) return blas;
  VkDeviceSize compactSize = 0;
  SM_VK(vkGetQueryPoolResults(ctx.device(), query.get(), 0, 1, sizeof compactSize, &compactSize,
                              sizeof compactSize,
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  if (compactSize == 0 || compactSize >= blas.bytes()) return blas;
  AccelerationStructure small =
      create(ctx, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, compactSize, name);
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    VkCopyAccelerationStructureInfoKHR copy{VK_STRUCTURE_TYPE_COPY_ACCELERATION_STRUCTURE_INFO_KHR};
    copy.src = blas.handle();
    copy.dst = small.handle();
    copy.mode = VK_COPY_ACCELERATION_STRUCTURE_MODE_COMPACT_KHR;
    ctx.fn().cmdCopyAccelerationStructure(cmd, &copy);
  });
  return small;
}

}  // namespace

AccelerationStructure AccelerationStructure::buildTriangles(
    const Context& ctx, const Buffer& positions, uint32_t vertexCount, const Buffer& indices,
    uint32_t triangleCount, bool compact, const std::string& name) {
  VkAccelerationStructureGeometryKHR geom{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  geom.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
  geom.flags = VK_GEOMETRY_OPAQUE_BIT_KHR;
  auto& tri = geom.geometry.triangles;
  tri.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR;
  tri.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
  tri.vertexData.deviceAddress = positions.address();
  tri.vertexStride = 3 * sizeof(float);
  tri.maxVertex = vertexCount ? vertexCount - 1 : 0;
  tri.indexType = VK_INDEX_TYPE_UINT32;
  tri.indexData.deviceAddress = indices.address();
  return buildBottomLevel(ctx, geom, triangleCount, compact, name, &AccelerationStructure::create);
}

AccelerationStructure AccelerationStructure::buildBoxes(const Context& ctx, const Buffer& aabbs,
                                                        uint32_t count, bool compact,
                                                        const std::string& name) {
  VkAccelerationStructureGeometryKHR geom{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  geom.geometryType = VK_GEOMETRY_TYPE_AABBS_KHR;
  geom.flags = 0;  // not opaque: every candidate box reaches the shader's exact test
  geom.geometry.aabbs.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_AABBS_DATA_KHR;
  geom.geometry.aabbs.data.deviceAddress = aabbs.address();
  geom.geometry.aabbs.stride = sizeof(VkAabbPositionsKHR);
  return buildBottomLevel(ctx, geom, count, compact, name, &AccelerationStructure::create);
}

VkDeviceSize AccelerationStructure::bottomLevelBuildBytes(const Context& ctx, bool boxes,
                                                          uint32_t count, uint32_t vertexCount) {
  // The size query ignores every device address, so the geometry needs none.
  VkAccelerationStructureGeometryKHR geom{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  if (boxes) {
    geom.geometryType = VK_GEOMETRY_TYPE_AABBS_KHR;
    geom.geometry.aabbs.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_AABBS_DATA_KHR;
    geom.geometry.aabbs.stride = sizeof(VkAabbPositionsKHR);
  } else {
    geom.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
    geom.flags = VK_GEOMETRY_OPAQUE_BIT_KHR;
    auto& tri = geom.geometry.triangles;
    tri.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR;
    tri.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
    tri.vertexStride = 3 * sizeof(float);
    tri.maxVertex = vertexCount ? vertexCount - 1 : 0;
    tri.indexType = VK_INDEX_TYPE_UINT32;
  }
  VkAccelerationStructureBuildGeometryInfoKHR build{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  build.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
  build.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR |
                VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_COMPACTION_BIT_KHR;
  build.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  build.geometryCount = 1;
  build.pGeometries = &geom;
  VkAccelerationStructureBuildSizesInfoKHR sizes{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  ctx.fn().getAccelerationStructureBuildSizes(
      ctx.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &build, &count, &sizes);
  return sizes.accelerationStructureSize + sizes.buildScratchSize;
}

AccelerationStructure AccelerationStructure::buildInstance(const Context& ctx,
                                                           const AccelerationStructure* blas,
                                                           const std::string& name) {
  VkAccelerationStructureInstanceKHR inst{};
  inst.transform.matrix[0][0] = inst.transform.matrix[1][1] = inst.transform.matrix[2][2] = 1.0f;
  inst.mask = 0xFF;
  inst.accelerationStructureReference = blas ? blas->address() : 0;
  Buffer instances(
      ctx, sizeof inst,
      VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR | kStorageUsage,
      MemoryUse::Device, name + " instance");
  instances.upload(&inst, sizeof inst);

  VkAccelerationStructureGeometryKHR geom{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  geom.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
  geom.flags = VK_GEOMETRY_OPAQUE_BIT_KHR;
  geom.geometry.instances.sType =
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR;
  geom.geometry.instances.data.deviceAddress = instances.address();
  VkAccelerationStructureBuildGeometryInfoKHR build{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  build.type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR;
  build.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
  build.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  build.geometryCount = 1;
  build.pGeometries = &geom;
  uint32_t count = blas ? 1 : 0;
  VkAccelerationStructureBuildSizesInfoKHR sizes{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  ctx.fn().getAccelerationStructureBuildSizes(
      ctx.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &build, &count, &sizes);
  AccelerationStructure tlas = create(ctx, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR,
                                      sizes.accelerationStructureSize, name);
  Buffer scratch(ctx, sizes.buildScratchSize, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::Device,
                 name + " scratch");
  build.dstAccelerationStructure = tlas.handle();
  build.scratchData.deviceAddress = scratch.address();
  VkAccelerationStructureBuildRangeInfoKHR range{count, 0, 0, 0};
  const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    ctx.fn().cmdBuildAccelerationStructures(cmd, 1, &build, &ranges);
  });
  return tlas;
}

}  // namespace sm::vk
