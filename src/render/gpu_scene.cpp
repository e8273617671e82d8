#include "render/gpu_scene.h"

#include "common/error.h"

namespace sm::render {
namespace {
constexpr VkBufferUsageFlags kAsInput =
    VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR;
}

GpuScene::GpuScene(const vk::Context& ctx, const prep::PreparedRank& r)
    : ctx_(ctx),
      compact_(r.compact),
      typesPresent_(r.typesPresent()),
      numVertices_(r.numVertices()),
      shellTriangles_(r.numShellTriangles()),
      origin_(r.frame.origin) {
  positions_ = vk::makeBuffer<float>(ctx, r.positions, "positions", kAsInput);
  scalars_ = vk::Buffer(ctx, numVertices_ * sizeof(float), vk::kStorageUsage, vk::MemoryUse::Device,
                        "scalars");
  shellIndices_ = vk::makeBuffer<uint32_t>(ctx, r.shellIndices, "shell indices", kAsInput);
  shellRefs_ = vk::makeBuffer<uint32_t>(ctx, r.shellRefs, "shell element refs");
  shellOther_ = vk::makeBuffer<uint32_t>(ctx, r.shellOther, "shell quad vertices");
  shellAdjacency_ = vk::makeBuffer<uint32_t>(ctx, r.shellAdjacency, "shell adjacency");
  static const char* kNames[4] = {"tetrahedra", "pyramids", "wedges", "hexahedra"};
  for (int t = 0; t < 4; ++t) {
    elements_[t] =
        vk::makeBuffer<uint32_t>(ctx, r.elements[t], std::string(kNames[t]) + " records");
    neighbors_[t] =
        vk::makeBuffer<uint32_t>(ctx, r.neighbors[t], std::string(kNames[t]) + " neighbours");
  }
  if (shellTriangles_ > 0) {
    if (shellTriangles_ > 0xFFFFFFFFull)
      throw Error("shell of ", shellTriangles_, " triangles: use more ranks");
    blas_ = vk::AccelerationStructure::buildTriangles(ctx, positions_, uint32_t(numVertices_),
                                                      shellIndices_, uint32_t(shellTriangles_),
                                                      true, "shell BLAS");
  }
  tlas_ =
      vk::AccelerationStructure::buildInstance(ctx, blas_.valid() ? &blas_ : nullptr, "shell TLAS");
  ++geometryBuilds_;
}

void GpuScene::setScalars(const std::vector<float>& values) {
  if (values.size() != numVertices_)
    throw Error("scalars for ", values.size(), " vertices, the scene has ", numVertices_);
  scalars_.upload(values.data(), values.size() * sizeof(float));
  ++scalarUploads_;
}

gpu::SceneRefs GpuScene::refs() const {
  gpu::SceneRefs s{};
  s.positions = positions_.address();
  s.scalars = scalars_.address();
  for (int t = 0; t < 4; ++t) {
    s.elements[t] = elements_[t].address();
    s.neighbors[t] = neighbors_[t].address();
  }
  s.shellIndices = shellIndices_.address();
  s.shellRefs = shellRefs_.address();
  s.shellOther = shellOther_.address();
  s.shellAdjacency = shellAdjacency_.address();
  return s;
}

uint64_t GpuScene::deviceBytes() const {
  uint64_t b = positions_.size() + scalars_.size() + shellIndices_.size() + shellRefs_.size() +
               shellOther_.size() + shellAdjacency_.size() + accelerationStructureBytes();
  for (int t = 0; t < 4; ++t) b += elements_[t].size() + neighbors_[t].size();
  return b;
}

}  // namespace sm::render
