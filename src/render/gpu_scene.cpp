#include "render/gpu_scene.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

#include "common/check.h"
#include "common/error.h"

namespace sm::render {
namespace {
constexpr VkBufferUsageFlags kAsInput =
    VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR;
}

std::vector<VkAabbPositionsKHR> shellBoxes(const prep::PreparedRank& r,
                                           std::span<const float> positions) {
  // From the shell's own vertices: a point no element uses may lie anywhere (up to FLT_MAX).
  float scale = 0.0f;
  for (uint32_t v : r.shellIndices)
    for (int k = 0; k < 3; ++k) scale = std::max(scale, std::abs(positions[3 * size_t(v) + k]));
  const float absolutePad = std::max(scale, 1e-30f) * 1e-6f;
  std::vector<VkAabbPositionsKHR> boxes(r.numShellTriangles());
  for (size_t t = 0; t < boxes.size(); ++t) {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (int k = 0; k < 3; ++k) {
      const float* p = &positions[3 * size_t(r.shellIndices[3 * t + k])];
      lo = glm::min(lo, glm::vec3(p[0], p[1], p[2]));
      hi = glm::max(hi, glm::vec3(p[0], p[1], p[2]));
    }
    glm::vec3 pad((hi.x - lo.x + hi.y - lo.y + hi.z - lo.z) * 1e-4f + absolutePad);
    lo -= pad;
    hi += pad;
    boxes[t] = {lo.x, lo.y, lo.z, hi.x, hi.y, hi.z};
  }
  return boxes;
}

GpuScene::GpuScene(const vk::Context& ctx, const prep::PreparedRank& r,
                   std::vector<float> positions, ShellGeometry shell)
    : ctx_(ctx),
      shell_(shell),
      compact_(r.compact),
      typesPresent_(r.typesPresent()),
      numVertices_(r.numVertices()),
      shellTriangles_(r.numShellTriangles()),
      origin_(r.frame.origin),
      scale_(r.frame.scale),
      positions_(std::move(positions)) {
  if (positions_.size() != 3 * numVertices_)
    throw Error("positions for ", positions_.size() / 3, " vertices, the rank has ", numVertices_);
  // The shell's vertices bound the elements (a union of elements reaches its extremes on its
  // boundary); points no element uses, however far, are not part of what is drawn.
  for (uint32_t v : r.shellIndices)
    bounds_.extend(glm::dvec3(positions_[3 * uint64_t(v)], positions_[3 * uint64_t(v) + 1],
                              positions_[3 * uint64_t(v) + 2]));
  vertices_[0] = vk::Buffer(ctx, std::max<uint64_t>(numVertices_, 1) * sizeof(glm::vec4),
                            vk::kStorageUsage, vk::MemoryUse::Device, "vertices");
  uploadVertices(vertices_[0], std::vector<float>(numVertices_, 0.0f));
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
    // A larger build is undefined behaviour on the device, not an error it reports.
    const uint64_t limit = std::min<uint64_t>(ctx.asPrimitiveLimit(), 0xFFFFFFFFull);
    if (shellTriangles_ > limit)
      throw Error("a shell of ", shellTriangles_, " triangles on this rank; the device's",
                  " acceleration structures hold at most ", limit, " (use more ranks)");
    if (shell == ShellGeometry::Triangles) {
      // The BLAS copies the triangles it is built from: the positions are input only.
      vk::Buffer input = vk::makeBuffer<float>(ctx, positions_, "positions (BLAS input)", kAsInput);
      blas_ = vk::AccelerationStructure::buildTriangles(ctx, input, uint32_t(numVertices_),
                                                        shellIndices_, uint32_t(shellTriangles_),
                                                        true, "shell BLAS (triangles)");
    } else {
      auto boxes = shellBoxes(r, positions_);
      vk::Buffer input = vk::makeBuffer<VkAabbPositionsKHR>(ctx, boxes, "shell boxes", kAsInput);
      blas_ = vk::AccelerationStructure::buildBoxes(ctx, input, uint32_t(boxes.size()), true,
                                                    "shell BLAS (boxes)");
    }
  }
  tlas_ =
      vk::AccelerationStructure::buildInstance(ctx, blas_.valid() ? &blas_ : nullptr, "shell TLAS");
  ++geometryBuilds_;
}

uint64_t GpuScene::requiredBytes(const vk::Context& ctx, const prep::PreparedRank& r,
                                 ShellGeometry shell) {
  auto bytes = [](const auto& v) {
    return std::max<uint64_t>(v.size() * sizeof(v[0]), 16);  // buffers hold 16 bytes at least
  };
  uint64_t b = std::max<uint64_t>(r.numVertices(), 1) * sizeof(glm::vec4) + bytes(r.shellIndices) +
               bytes(r.shellRefs) + bytes(r.shellOther) + bytes(r.shellAdjacency);
  for (int t = 0; t < 4; ++t) b += bytes(r.elements[t]) + bytes(r.neighbors[t]);
  const uint64_t tris = r.numShellTriangles();
  if (tris > 0 && tris <= 0xFFFFFFFFull) {
    const bool boxes = shell == ShellGeometry::Boxes;
    // Triangles: the positions are copied to the device as the BLAS's input.
    b += boxes ? tris * sizeof(VkAabbPositionsKHR)
               : std::max<uint64_t>(3 * r.numVertices() * sizeof(float), 16);
    b += vk::AccelerationStructure::bottomLevelBuildBytes(ctx, boxes, uint32_t(tris),
                                                          uint32_t(r.numVertices()));
  }
  return b;
}

// Position and scalar interleaved per vertex (scene_access.glsl, vertexRecord): a new step rewrites
// the positions too, 16 bytes per vertex instead of 4, for half the gathers per marching step.
void GpuScene::uploadVertices(vk::Buffer& buffer, std::span<const float> scalars) const {
  std::vector<glm::vec4> v(std::max<uint64_t>(numVertices_, 1), glm::vec4(0.0f));
  for (uint64_t i = 0; i < numVertices_; ++i)
    v[i] = glm::vec4(positions_[3 * i], positions_[3 * i + 1], positions_[3 * i + 2], scalars[i]);
  buffer.upload(v.data(), v.size() * sizeof(glm::vec4));
}

void GpuScene::setScalars(const std::vector<float>& values) {
  if (values.size() != numVertices_)
    throw Error("scalars for ", values.size(), " vertices, the scene has ", numVertices_);
  uploadVertices(vertices_[front_], values);
  ++scalarUploads_;
}

void GpuScene::stageScalars(std::span<const float> values) {
  if (values.size() != numVertices_)
    throw Error("scalars for ", values.size(), " vertices, the scene has ", numVertices_);
  vk::Buffer& back = vertices_[1 - front_];
  if (!back.valid())
    back = vk::Buffer(ctx_, std::max<uint64_t>(numVertices_, 1) * sizeof(glm::vec4),
                      vk::kStorageUsage, vk::MemoryUse::Device, "vertices (next step)");
  uploadVertices(back, values);
  ++scalarUploads_;
}

void GpuScene::swapScalars() {
  SM_CHECK(vertices_[1 - front_].valid());
  front_ = 1 - front_;
}

gpu::SceneRefs GpuScene::refs() const {
  gpu::SceneRefs s{};
  s.vertices = vertices_[front_].address();
  for (int t = 0; t < 4; ++t) {
    s.elements[t] = elements_[t].address();
    s.neighbors[t] = neighbors_[t].address();
    // The shaders read records and a tetrahedron's neighbours as 64-bit words (each buffer has
    // its own allocation, which any implementation aligns for every resource it supports).
    SM_CHECK(s.elements[t] % 8 == 0 && s.neighbors[t] % 8 == 0);
  }
  s.shellIndices = shellIndices_.address();
  s.shellRefs = shellRefs_.address();
  s.shellOther = shellOther_.address();
  s.shellAdjacency = shellAdjacency_.address();
  return s;
}

uint64_t GpuScene::deviceBytes() const {
  uint64_t b = vertices_[0].size() + vertices_[1].size() + shellIndices_.size() +
               shellRefs_.size() + shellOther_.size() + shellAdjacency_.size() +
               accelerationStructureBytes();
  for (int t = 0; t < 4; ++t) b += elements_[t].size() + neighbors_[t].size();
  return b;
}

}  // namespace sm::render
