// The Vulkan layer on the real device (lavapipe in CI): compute through buffer addresses,
// specialization constants, the staging path, validation counting, and the ray-query facing
// convention the shell traversal is built on.
#include <algorithm>

#include <gtest/gtest.h>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "test_shaders.h"
#include "vk/accel.h"
#include "vk/buffer.h"
#include "vk/pipeline.h"
#include "vk/vk_error.h"

namespace sm::vk {
namespace {

struct ScalePush {
  uint64_t data;
  uint32_t n;
  float factor;
};

void runScaleAdd(bool forceStaging) {
  ContextOptions o;
  o.rayTracing = false;
  o.forceStaging = forceStaging;
  Context ctx(o);
  EXPECT_EQ(ctx.forceStaging(), forceStaging);
  std::vector<float> v(1000);
  for (size_t i = 0; i < v.size(); ++i) v[i] = float(i);
  Buffer buf = makeBuffer<float>(ctx, v, "values");
  if (forceStaging) {
    EXPECT_EQ(buf.mapped(), nullptr);
  }
  ComputePipeline p(ctx,
                    {"scale_add", test::spv::scale_add(), {{0, 7u}}, sizeof(ScalePush), false});
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    p.dispatch(cmd, groupsFor(v.size(), 64), 1, 1,
               ScalePush{buf.address(), uint32_t(v.size()), 2.0f});
  });
  auto out = buf.download<float>();
  for (size_t i = 0; i < v.size(); ++i) ASSERT_EQ(out[i], 2.0f * i + 7.0f) << i;
  EXPECT_EQ(ctx.validationErrors(), 0u);
  EXPECT_EQ(ctx.validationWarnings(), 0u);
}

TEST(Vk, ComputeThroughBufferAddresses) {
  runScaleAdd(false);
}
TEST(Vk, StagingPath) {
  runScaleAdd(true);
}

TEST(Vk, ValidationIsOnInTests) {
  ContextOptions o;
  o.rayTracing = false;
  Context ctx(o);
  EXPECT_TRUE(ctx.validationEnabled()) << "ctest must run GPU tests with SHELLMARCH_VALIDATION=1";
}

// One process making contexts one after another, as in-process ranks, test suites and the in situ
// library's users do, keeps finding the driver. NVIDIA's (580, H100) could not be loaded again
// once the loader had unloaded it, and from about the thirtieth context on every one failed;
// Context now holds the drivers loaded (holdDriversLoaded in context.cpp). Lavapipe reloads
// fine, so this guards GPU machines.
TEST(Vk, ContextsMadeOneAfterAnotherKeepFindingTheDriver) {
  ContextOptions o;
  o.rayTracing = false;
  for (uint32_t i = 0; i < 64; ++i) {
    Context ctx(o);
    Buffer b = makeBuffer<uint32_t>(ctx, std::vector<uint32_t>{i, ~i}, "round trip");
    const std::vector<uint32_t> got = b.download<uint32_t>();
    ASSERT_GE(got.size(), 2u);
    ASSERT_EQ(got[0], i) << "context " << i;
    ASSERT_EQ(got[1], ~i) << "context " << i;
    ASSERT_EQ(ctx.validationErrors(), 0u) << "context " << i;
  }
}

// A buffer's size and its memory are checked against the device's maxBufferSize and
// maxMemoryAllocationSize by size alone (nothing allocated): at each limit it passes, one byte more
// is refused in one line naming the buffer, its size, the limit and how many more ranks would fit.
TEST(BufferLimits, AtEachLimitABufferPassesAndOneByteMoreIsRefused) {
  const uint64_t gib = uint64_t(1) << 30;
  const BufferLimits limits{4 * gib - 1, 2 * gib};  // lavapipe's
  EXPECT_EQ(bufferSizeError("tetrahedra records", 2 * gib, 2 * gib, limits), "");
  EXPECT_EQ(bufferSizeError("tetrahedra records", 2 * gib + 1, 2 * gib + 1, limits),
            "buffer 'tetrahedra records' needs 2.00 GiB (2147483649 bytes), more than the device's "
            "largest allocation (maxMemoryAllocationSize, 2.00 GiB (2147483648 bytes)); use more "
            "ranks (at least 2 times as many)");
  // The memory the device asks for may be more than the buffer holds: that is checked too.
  EXPECT_NE(bufferSizeError("vertices", 2 * gib, 2 * gib + 256, limits), "");
  const BufferLimits sizeOnly{4 * gib - 1, UINT64_MAX};
  EXPECT_EQ(bufferSizeError("shell boxes", 4 * gib - 1, 4 * gib - 1, sizeOnly), "");
  const std::string msg = bufferSizeError("shell boxes", 4 * gib, 4 * gib, sizeOnly);
  EXPECT_NE(msg.find("'shell boxes' needs 4.00 GiB (4294967296 bytes)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("largest buffer (maxBufferSize, 4.00 GiB (4294967295 bytes))"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("use more ranks (at least 2 times as many)"), std::string::npos) << msg;
  // Far past: the ranks needed grow with the size; a device that gives no limit takes anything.
  const BufferLimits allocationOnly{UINT64_MAX, 2 * gib};
  EXPECT_NE(bufferSizeError("hexahedra records", 5 * gib, 5 * gib, allocationOnly)
                .find("at least 3 times"),
            std::string::npos);
  EXPECT_EQ(bufferSizeError("any", UINT64_MAX, UINT64_MAX, BufferLimits{}), "");
}

// On the device: the context reads its limits, and a buffer one byte past them is refused before
// anything is created or allocated (no device memory held, no validation message).
TEST(Vk, BufferPastTheDeviceLimitsIsRefusedBeforeAllocating) {
  ContextOptions o;
  o.rayTracing = false;
  Context ctx(o);
  const BufferLimits& limits = ctx.bufferLimits();
  EXPECT_GE(limits.maxAllocationSize, uint64_t(1) << 30);  // the spec's minimum
  EXPECT_GE(limits.maxBufferSize, uint64_t(1) << 30);
  const uint64_t limit = std::min(limits.maxBufferSize, limits.maxAllocationSize);
  ASSERT_LT(limit, UINT64_MAX) << "the device gives no buffer limit";
  const uint64_t before = ctx.deviceMemoryInUse();
  try {
    Buffer b(ctx, limit + 1, kStorageUsage, MemoryUse::Device, "too large");
    ADD_FAILURE() << "a buffer of " << limit + 1 << " bytes was made";
  } catch (const BufferLimitError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("buffer 'too large' needs ", 0), 0u) << msg;
    EXPECT_NE(msg.find(std::to_string(limit) + " bytes"), std::string::npos) << msg;
    EXPECT_NE(msg.find("use more ranks"), std::string::npos) << msg;
    EXPECT_EQ(e.requested(), limit + 1);
  }
  EXPECT_EQ(ctx.deviceMemoryInUse(), before);
  EXPECT_EQ(ctx.validationErrors(), 0u);
}

TEST(Vk, DeviceErrorListsWhatEachDeviceLacks) {
  ContextOptions o;
  o.device = "no-such-device-name";
  try {
    Context ctx(o);
    FAIL() << "expected an error";
  } catch (const VulkanError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("device 'no-such-device-name': no usable device matches"), std::string::npos)
        << msg;
    EXPECT_NE(msg.find("[0]"), std::string::npos) << msg;
  }
}

// Rows of at most maxX groups, as few rows as hold them, rows as short as those rows allow.
TEST(Vk, GroupGridSplitsDispatchesIntoRows) {
  auto same = [](GroupGrid g, uint32_t x, uint32_t y) { return g.x == x && g.y == y; };
  EXPECT_TRUE(same(groupGrid(0, 65535, 65535), 0, 0));
  EXPECT_TRUE(same(groupGrid(1, 65535, 65535), 1, 1));
  EXPECT_TRUE(same(groupGrid(65535, 65535, 65535), 65535, 1));
  EXPECT_TRUE(same(groupGrid(65536, 65535, 65535), 32768, 2));  // a 2048² image, 64 per group
  EXPECT_TRUE(same(groupGrid(10, 4, 65535), 4, 3));
  for (uint64_t groups : {2ull, 7ull, 65537ull, 131071ull, 4194304ull, 4294836225ull}) {
    GroupGrid g = groupGrid(groups, 65535, 65535);
    const uint64_t cells = uint64_t(g.x) * g.y;
    EXPECT_LE(g.x, 65535u) << groups;
    EXPECT_GE(cells, groups) << groups;
    EXPECT_LT(cells - groups, g.y) << groups;  // fewer idle groups than rows
  }
  EXPECT_THROW(groupGrid(4294836226ull, 65535, 65535), VulkanError);  // one more than 65535²
  EXPECT_THROW(groupGrid(1, 0, 65535), VulkanError);
}

struct IdsPush {
  uint64_t hits;
  uint32_t n;
};

// More groups than one row holds: every item's invocation runs once, and the grid's idle groups
// (fewer than its rows) see indices past the items.
TEST(Vk, DispatchItemsBeyondOneRowReachesEveryItemOnce) {
  ContextOptions o;
  o.rayTracing = false;
  Context ctx(o);
  // Rows of kGridRowGroups also on devices that take more groups in x (NVIDIA: 2^31 - 1, where
  // 2 * maxX + 3 items overflowed 32 bits and ran in one row).
  const uint32_t maxX =
      std::min(ctx.properties().limits.maxComputeWorkGroupCount[0], kGridRowGroups);
  const uint32_t n = 2 * maxX + 3;  // maxX + 2 groups of 2
  std::vector<uint32_t> zeros(n + 1, 0u);
  Buffer hits = makeBuffer<uint32_t>(ctx, zeros, "hits");
  ComputePipeline p(ctx, {"linear_ids", test::spv::linear_ids(), {}, sizeof(IdsPush), false});
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    p.dispatchItems(cmd, n, 2, IdsPush{hits.address(), n});
  });
  std::vector<uint32_t> got = hits.download<uint32_t>();
  size_t wrong = 0;
  for (uint32_t i = 0; i < n; ++i) wrong += got[i] != 1u;
  EXPECT_EQ(wrong, 0u);
  const GroupGrid g =
      groupGrid((n + 1) / 2, maxX, ctx.properties().limits.maxComputeWorkGroupCount[1]);
  EXPECT_EQ(g.y, 2u);
  EXPECT_EQ(got[n], uint64_t(g.x) * g.y * 2 - n);
  EXPECT_EQ(ctx.validationErrors(), 0u);
}

struct CarryPush {
  uint64_t counter;
  uint32_t add;
};

// The renderer's 64-bit sample and step counters (counters.glsl): started just below 2^32 and
// then past 2^33, 64 000 adds of 70 000 (4.48 G in all) must carry exactly.
TEST(Vk, CountersCarryPast32Bits) {
  ContextOptions o;
  o.rayTracing = false;
  Context ctx(o);
  ComputePipeline p(ctx,
                    {"carry_counter", test::spv::carry_counter(), {}, sizeof(CarryPush), false});
  for (uint64_t start : {0xffff0000ull, 0x2fffffff0ull}) {
    std::vector<uint32_t> init = {uint32_t(start), uint32_t(start >> 32)};
    Buffer c = makeBuffer<uint32_t>(ctx, init, "counter");
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      p.dispatch(cmd, 1000, 1, 1, CarryPush{c.address(), 70000u});
    });
    std::vector<uint32_t> got = c.download<uint32_t>();
    EXPECT_EQ(uint64_t(got[1]) << 32 | got[0], start + 64000ull * 70000ull) << start;
  }
  EXPECT_EQ(ctx.validationErrors(), 0u);
}

struct TracePush {
  uint64_t rays, hits;
  uint32_t n, flags;
  float z0, dz;
};

// Two triangles at z = 0 and z = 1 over the unit square, wound in opposite directions.
TEST(Vk, RayQueryCullsFrontFacesAsTheShellTraversalAssumes) {
  Context ctx;
  ASSERT_TRUE(ctx.hasRayQuery());
  // Triangle 0 at z=0: (0,0),(0,1),(1,0): normal -z, faces a ray going +z (front-facing:
  // dot(d, n) < 0). Triangle 1 at z=1: (0,0),(1,0),(0,1): normal +z, back-facing for that ray.
  std::vector<float> pos = {0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1};
  std::vector<uint32_t> idx = {0, 1, 2, 3, 4, 5};
  const VkBufferUsageFlags asInput =
      VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR;
  Buffer vb = makeBuffer<float>(ctx, pos, "positions", asInput);
  Buffer ib = makeBuffer<uint32_t>(ctx, idx, "indices", asInput);
  auto blas = AccelerationStructure::buildTriangles(ctx, vb, 6, ib, 2, true, "blas");
  auto tlas = AccelerationStructure::buildInstance(ctx, &blas, "tlas");
  std::vector<glm::vec2> rays = {{0.25f, 0.25f}, {0.9f, 0.9f}};
  Buffer rb = makeBuffer<glm::vec2>(ctx, rays, "rays");
  Buffer hb(ctx, rays.size() * sizeof(glm::vec4), kStorageUsage, MemoryUse::Device, "hits");
  ComputePipeline p(ctx, {"trace_rays", test::spv::trace_rays(), {}, sizeof(TracePush), true});
  p.setAccelerationStructure(tlas.handle());
  auto trace = [&](uint32_t flags, float z0 = -1.0f, float dz = 1.0f) {
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      p.dispatch(cmd, 1, 1, 1,
                 TracePush{rb.address(), hb.address(), uint32_t(rays.size()), flags, z0, dz});
    });
    return hb.download<glm::vec4>();
  };
  const uint32_t kOpaque = 0x1,
                 kCullFront = 0x20;  // gl_RayFlagsOpaqueEXT, ...CullFrontFacingTrianglesEXT
  auto all = trace(kOpaque);
  EXPECT_FLOAT_EQ(all[0].x, 1.0f);  // first hit: z = 0 at t = 1
  EXPECT_EQ(all[0].y, 0.0f);
  EXPECT_EQ(all[0].z, 1.0f);  // front face
  EXPECT_EQ(all[1].w, 0.0f);  // (0.9, 0.9) is outside both triangles
  auto culled = trace(kOpaque | kCullFront);
  EXPECT_FLOAT_EQ(culled[0].x, 2.0f);  // front face culled: the back-facing one at z = 1
  EXPECT_EQ(culled[0].y, 1.0f);
  EXPECT_EQ(culled[0].z, 0.0f);
  // Backward rays (along -z from z = 3): now triangle 1 (normal +z) faces them and is culled.
  auto back = trace(kOpaque | kCullFront, 3.0f, -1.0f);
  EXPECT_FLOAT_EQ(back[0].x, 3.0f);
  EXPECT_EQ(back[0].y, 0.0f);
  EXPECT_EQ(back[0].z, 0.0f);
  EXPECT_GT(blas.bytes(), 0u);
  EXPECT_EQ(ctx.validationErrors(), 0u);
  EXPECT_EQ(ctx.validationWarnings(), 0u);
}

}  // namespace
}  // namespace sm::vk

namespace sm::vk {
namespace {
// Pipelines from one SPIR-V module that differ only in specialization constants must differ
// (the renderer builds count and store variants of one traversal shader this way).
TEST(Vk, SpecializationVariantsOfOneModuleStayDistinct) {
  ContextOptions o;
  o.rayTracing = false;
  Context ctx(o);
  std::vector<float> v(64, 1.0f);
  Buffer a = makeBuffer<float>(ctx, v, "a"), b = makeBuffer<float>(ctx, v, "b");
  ComputePipeline p7(ctx, {"add7", test::spv::scale_add(), {{0, 7u}}, sizeof(ScalePush), false});
  ComputePipeline p9(ctx, {"add9", test::spv::scale_add(), {{0, 9u}}, sizeof(ScalePush), false});
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    p7.dispatch(cmd, 1, 1, 1, ScalePush{a.address(), 64, 1.0f});
    p9.dispatch(cmd, 1, 1, 1, ScalePush{b.address(), 64, 1.0f});
  });
  EXPECT_EQ(a.download<float>()[0], 8.0f);
  EXPECT_EQ(b.download<float>()[0], 10.0f);
}
}  // namespace
}  // namespace sm::vk
