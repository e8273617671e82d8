#include "compositor_cases.h"

#include <gtest/gtest.h>

namespace sm::comp::test {
namespace {

constexpr double kTolerance = 1e-4;  // float32 blending of a few hundred fragments

std::string describe(const CompositorOptions& o, const World& w) {
  const char* mode[] = {"two-pass", "fixed-drop", "fixed-merge"};
  return std::string(mode[int(o.mode)]) + (o.encoding == Encoding::Float ? " float" : " rgba8") +
         " K=" + std::to_string(o.fixedK) + " " + std::to_string(w.width) + "x" +
         std::to_string(w.height) + " on " + std::to_string(w.ranks) + " ranks, " +
         ownershipName(o.ownership) + " ownership";
}

WorldSpec specFor(comm::Communicator* comm, int width, int height, uint32_t seed) {
  WorldSpec s;
  s.width = width;
  s.height = height;
  s.ranks = ranksOf(comm);
  s.seed = seed;
  return s;
}

}  // namespace

int rankOf(comm::Communicator* comm) {
  return comm ? comm->rank() : 0;
}
int ranksOf(comm::Communicator* comm) {
  return comm ? comm->size() : 1;
}

RankRig::RankRig(comm::Communicator* comm, const vk::Context& ctx, int width, int height,
                 const CompositorOptions& options)
    : comm_(comm),
      compositor_(std::make_unique<DeepCompositor>(ctx, comm, width, height, options)),
      writer_(std::make_unique<ListWriter>(*compositor_)) {}

std::vector<glm::vec4> RankRig::run(const World& w, CompositeMethod method) {
  writer_->write(w.raw[size_t(rankOf(comm_))]);
  return compositor_->composite(method);
}

void checkSmallImages(comm::Communicator* comm, const vk::Context& ctx) {
  for (auto [width, height] : {std::pair{1, 1}, std::pair{17, 13}}) {
    for (auto [e, own] : {std::pair{Encoding::Float, PixelOwnership::Interleaved},
                          {Encoding::Rgba8, PixelOwnership::Interleaved},
                          {Encoding::Float, PixelOwnership::Ranges}}) {
      CompositorOptions o;
      o.encoding = e;
      o.ownership = own;
      RankRig rig(comm, ctx, width, height, o);
      for (uint32_t seed : {1u, 2u, 3u}) {
        WorldSpec s = specFor(comm, width, height, seed);
        s.longFraction = width == 1 ? 1.0 : 0.05;  // the 1x1 image gets lists up to 100 long
        s.emptyFraction = width == 1 && seed == 3 ? 1.0 : 0.2;
        World w = makeWorld(s);
        std::vector<glm::vec4> image = rig.run(w);
        if (rankOf(comm) == 0)
          expectImageNear(image, deepReference(w, o), kTolerance, describe(o, w));
      }
    }
  }
}

void checkLargeImage(comm::Communicator* comm, const vk::Context& ctx) {
  WorldSpec s = specFor(comm, 256, 256, 11);
  s.maxShort = 3;
  s.longFraction = 0.002;
  World w = makeWorld(s);
  std::vector<glm::vec4> first;
  for (PixelOwnership own : {PixelOwnership::Interleaved, PixelOwnership::Ranges}) {
    CompositorOptions o;
    o.ownership = own;
    RankRig rig(comm, ctx, s.width, s.height, o);
    std::vector<glm::vec4> image = rig.run(w);
    if (rankOf(comm) != 0) continue;
    expectImageNear(image, deepReference(w, o), kTolerance, describe(o, w));
    // Which rank merges a pixel's lists does not change the merge.
    if (first.empty())
      first = image;
    else
      EXPECT_TRUE(image == first) << "ownerships give different images: " << describe(o, w);
  }
}

void checkBeyondOneDispatchRow(comm::Communicator* comm, const vk::Context& ctx) {
  CompositorOptions o;
  // 4 196 352 pixels: 65 568 groups of 64, past the 65 535 a dispatch row may hold. Sparse, so
  // that the world and its reference stay small.
  WorldSpec s = specFor(comm, 2048, 2049, 12);
  s.emptyFraction = 0.9;
  s.maxShort = s.maxLong = 2;
  s.longFraction = 0.0;
  World w = makeWorld(s);
  RankRig rig(comm, ctx, s.width, s.height, o);
  std::vector<glm::vec4> image = rig.run(w);
  if (rankOf(comm) == 0) expectImageNear(image, deepReference(w, o), kTolerance, describe(o, w));
}

void checkFixedLists(comm::Communicator* comm, const vk::Context& ctx) {
  for (ListMode mode : {ListMode::FixedDrop, ListMode::FixedMerge}) {
    for (uint32_t k : {1u, 3u}) {
      for (Encoding e : {Encoding::Float, Encoding::Rgba8}) {
        CompositorOptions o;
        o.mode = mode;
        o.fixedK = k;
        o.encoding = e;
        WorldSpec s = specFor(comm, 17, 13, 20 + k);
        s.maxShort = 8;  // most lists overflow K
        World w = makeWorld(s);
        RankRig rig(comm, ctx, s.width, s.height, o);
        std::vector<glm::vec4> image = rig.run(w);
        // Merging re-quantises rgba8 fragments; a rounding flip of one level is allowed there.
        const bool requantised = mode == ListMode::FixedMerge && e == Encoding::Rgba8;
        if (rankOf(comm) == 0)
          expectImageNear(image, deepReference(w, o), requantised ? 2.0 / 255 : kTolerance,
                          describe(o, w));
        EXPECT_LE(rig.compositor().stats().longestList, k);
        // The lists on the device are what the host model of the interface stores.
        std::vector<uint32_t> counts;
        rig.compositor().downloadCounts(counts);
        EXPECT_EQ(counts, storedLists(w.raw[size_t(rankOf(comm))], o).counts) << describe(o, w);
      }
    }
  }
}

void checkCounterBoundaries(comm::Communicator* comm, const vk::Context& ctx) {
  const bool exchange = ranksOf(comm) > 1;
  CompositorOptions o;
  RankRig rig(comm, ctx, 5, 3, o);
  const int last = ranksOf(comm) - 1;
  for (auto [longest, bits] :
       {std::pair{3u, 2u}, {4u, 4u}, {15u, 4u}, {16u, 8u}, {255u, 8u}, {256u, 32u}}) {
    WorldSpec s = specFor(comm, 5, 3, longest);
    s.maxShort = 2;
    s.longFraction = 0;
    s.zeroOpacityFraction = 0;
    World w = makeWorld(s);
    // The longest list lives on the last rank only: every rank must learn it from the allreduce.
    std::vector<DcFragment> list;
    for (uint32_t i = 0; i < longest; ++i)
      list.push_back({glm::vec4(0.01f, 0.0f, 0.005f, 0.01f), 0.5f + 0.125f * float(i)});
    setList(w, last, 7, list);
    std::vector<glm::vec4> image = rig.run(w);
    const std::string label = "longest list " + std::to_string(longest);
    EXPECT_EQ(rig.compositor().stats().counterBits, exchange ? bits : 0u) << label;
    uint32_t mine = 0;
    for (uint32_t c : storedLists(w.raw[size_t(rankOf(comm))], o).counts) mine = std::max(mine, c);
    EXPECT_EQ(rig.compositor().stats().longestList, mine) << label;
    if (rankOf(comm) == last) {
      EXPECT_EQ(mine, longest);
    }
    if (rankOf(comm) == 0) expectImageNear(image, deepReference(w, o), kTolerance, label);
  }
  // Forced widths: 32 bits always fits; 2 bits cannot hold a list of 4 and fails on every rank.
  WorldSpec s = specFor(comm, 5, 3, 99);
  s.maxShort = 4;
  s.longFraction = 0;
  World w = makeWorld(s);
  setList(w, last, 2, std::vector<DcFragment>(4, {glm::vec4(0.1f, 0.1f, 0.1f, 0.1f), 0.25f}));
  o.counterBits = 32;
  RankRig forced(comm, ctx, 5, 3, o);
  std::vector<glm::vec4> image = forced.run(w);
  EXPECT_EQ(forced.compositor().stats().counterBits, exchange ? 32u : 0u);
  if (rankOf(comm) == 0) expectImageNear(image, deepReference(w, o), kTolerance, "forced 32 bits");
  o.counterBits = 2;
  RankRig tooSmall(comm, ctx, 5, 3, o);
  if (exchange) {
    EXPECT_THROW(tooSmall.run(w), std::invalid_argument);
  }
  o.counterBits = 3;
  EXPECT_THROW(RankRig(comm, ctx, 5, 3, o).run(w), std::invalid_argument)
      << "3-bit counters are not an encoding";
}

}  // namespace sm::comp::test
