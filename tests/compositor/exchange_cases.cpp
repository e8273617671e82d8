// Shared test bodies, continued: single-fragment compositing, statistics, buffer growth and the
// in-memory merge.
#include <gtest/gtest.h>

#include "compositor/exchange_plan.h"
#include "compositor/tools/image_compare.h"
#include "compositor/tools/replay.h"
#include "compositor_cases.h"

namespace sm::comp::test {
namespace {

constexpr double kTolerance = 1e-4;

const glm::vec4 kRankColor[] = {{0.5f, 0.0f, 0.0f, 0.5f},
                                {0.0f, 0.5f, 0.0f, 0.5f},
                                {0.0f, 0.0f, 0.5f, 0.5f},
                                {0.4f, 0.4f, 0.0f, 0.5f}};

// Pixels p % 3 == 0: every rank's three fragments alternate with the other ranks' along the ray;
// p % 3 == 1: one fragment per rank; p % 3 == 2: empty.
World interleavedWorld(int ranks) {
  World w{9, 7, ranks, std::vector<HostLists>(size_t(ranks))};
  for (uint64_t p = 0; p < w.pixels(); ++p) {
    for (int r = 0; r < ranks; ++r) {
      HostLists& l = w.raw[size_t(r)];
      const uint32_t n = p % 3 == 0 ? 3 : p % 3 == 1 ? 1 : 0;
      for (uint32_t k = 0; k < n; ++k)
        l.fragments.push_back({kRankColor[r % 4], float(r + int(k) * ranks)});
      l.counts.push_back(n);
    }
  }
  return w;
}

}  // namespace

void checkSingleFragment(comm::Communicator* comm, const vk::Context& ctx) {
  const int R = ranksOf(comm);
  World w = interleavedWorld(R);
  CompositorOptions o;
  RankRig rig(comm, ctx, w.width, w.height, o);
  std::vector<glm::vec4> deep = rig.run(w, CompositeMethod::Deep);
  std::vector<glm::vec4> single = rig.run(w, CompositeMethod::SingleFragment);
  if (rankOf(comm) != 0) return;
  expectImageNear(deep, deepReference(w, o), kTolerance, "deep, interleaved");
  expectImageNear(single, singleFragmentReference(w, o), kTolerance, "single fragment");
  std::vector<float> diff = l2Difference(deep, single);
  for (uint64_t p = 0; p < w.pixels(); ++p) {
    if (p % 3 == 0 && R > 1)
      EXPECT_GT(diff[p], 0.05f) << "interleaved pixel " << p << " must differ";
    else
      EXPECT_LT(diff[p], 1e-5f) << "pixel " << p << " has no interleaving";
  }
  std::vector<glm::vec4> map = heatmap(std::span<const float>(diff));
  ASSERT_EQ(map.size(), w.pixels());
  EXPECT_EQ(map[1], glm::vec4(0, 0, 0, 1)) << "no difference maps to black";
  if (R > 1) {
    EXPECT_GT(map[0].r + map[0].g, 1.0f) << "the largest differences are bright";
  }
}

void checkStatistics(comm::Communicator* comm, const vk::Context& ctx) {
  const int R = ranksOf(comm), me = rankOf(comm);
  struct Case {
    Encoding e;
    PixelOwnership own;
    bool sparse;  // few pixels with fragments: zero-run coded counts
  };
  for (auto [e, own, sparse] : {Case{Encoding::Float, PixelOwnership::Interleaved, false},
                                Case{Encoding::Rgba8, PixelOwnership::Interleaved, false},
                                Case{Encoding::Rgba8, PixelOwnership::Ranges, false},
                                Case{Encoding::Float, PixelOwnership::Interleaved, true}}) {
    CompositorOptions o;
    o.encoding = e;
    o.ownership = own;
    WorldSpec s;
    s.ranks = R;
    s.seed = 5;
    if (sparse) {
      s.width = 96;
      s.height = 64;
      s.emptyFraction = 0.98;
    }
    World w = makeWorld(s);
    std::vector<HostLists> stored;
    for (const HostLists& r : w.raw) stored.push_back(storedLists(r, o));
    RankRig rig(comm, ctx, w.width, w.height, o);
    const std::vector<glm::vec4> image = rig.run(w);
    const CompositeStats& st = rig.compositor().stats();
    uint64_t fragments = 0, nonEmpty = 0;
    uint32_t longest = 0;
    for (uint32_t c : stored[size_t(me)].counts) {
      fragments += c;
      nonEmpty += c > 0;
      longest = std::max(longest, c);
    }
    EXPECT_EQ(st.fragments, fragments);
    EXPECT_EQ(st.nonEmptyPixels, nonEmpty);
    EXPECT_EQ(st.longestList, longest);
    EXPECT_DOUBLE_EQ(st.fragmentsPerNonEmptyPixel(), double(fragments) / double(nonEmpty));
    EXPECT_EQ(st.bytesSent, st.countBytesSent + st.fragmentBytesSent);
    std::vector<CompositeStats> all = rig.compositor().gatherStats();
    std::vector<std::vector<uint32_t>> heat = rig.compositor().gatherCounts();
    if (me != 0) {
      EXPECT_TRUE(all.empty() && heat.empty()) << "gathered on rank 0 only";
      continue;
    }
    ReplayResult replay =
        replayExchange(w.pixels(), R, e, 0, o.ownership,
                       [&](int r, std::vector<uint32_t>& c) { c = stored[size_t(r)].counts; });
    ASSERT_EQ(all.size(), size_t(R));
    ASSERT_EQ(heat.size(), size_t(R));
    for (int r = 0; r < R; ++r) {
      const ReplayRank& want = replay.ranks[size_t(r)];
      EXPECT_EQ(all[size_t(r)].fragments, want.fragments)
          << "rank " << r << ", " << ownershipName(own);
      EXPECT_EQ(all[size_t(r)].countBytesSent, want.countBytesSent) << "rank " << r;
      EXPECT_EQ(all[size_t(r)].fragmentBytesSent, want.fragmentBytesSent) << "rank " << r;
      EXPECT_EQ(all[size_t(r)].fragmentsComposited, want.fragmentsComposited) << "rank " << r;
      EXPECT_EQ(all[size_t(r)].counterBits, R > 1 ? replay.counterBits : 0u);
      EXPECT_EQ(heat[size_t(r)], stored[size_t(r)].counts) << "heatmap of rank " << r;
    }
    if (R == 1) {
      EXPECT_EQ(all[0].bytesSent, 0u) << "one rank exchanges nothing";
    } else {
      EXPECT_GT(all[0].fragmentBytesSent, 0u);
    }
    if (sparse && R > 1) {
      // Zero runs instead of a counter per pixel: well below the packed counters' bytes.
      const PixelRanges ranges(w.pixels(), R, own);
      for (int r = 0; r < R; ++r)
        EXPECT_LT(all[size_t(r)].countBytesSent * 2,
                  planCountExchange(ranges, r, replay.counterBits).transfer.sentToOthers(r))
            << "rank " << r;
      expectImageNear(image, deepReference(w, o), kTolerance, "sparse world, zero-run counts");
    }
    uint64_t summed = 0, composited = 0;
    for (uint32_t c : sumCounts(heat)) summed += c;
    for (const CompositeStats& r : all) composited += r.fragmentsComposited;
    uint64_t total = 0;
    for (const HostLists& l : stored) total += l.fragments.size();
    EXPECT_EQ(summed, total) << "combined heatmap";
    EXPECT_EQ(composited, total) << "every fragment is composited by exactly one rank";
  }
}

void checkBuffersOnlyGrow(comm::Communicator* comm, const vk::Context& ctx) {
  CompositorOptions o;
  RankRig rig(comm, ctx, 17, 13, o);
  WorldSpec big;
  big.ranks = ranksOf(comm);
  big.maxShort = 8;
  WorldSpec small = big;
  small.maxShort = 2;
  small.longFraction = 0;
  small.seed = 2;
  World a = makeWorld(big), b = makeWorld(small);
  uint64_t afterFirst = 0;
  int frame = 0;
  for (const World* w : {&a, &b, &b, &a}) {
    std::vector<glm::vec4> image = rig.run(*w);
    if (rankOf(comm) == 0)
      expectImageNear(image, deepReference(*w, o), kTolerance, "frame " + std::to_string(frame));
    if (frame++ == 0) afterFirst = rig.compositor().allocations();
  }
  EXPECT_EQ(rig.compositor().allocations(), afterFirst) << "frames no larger than the first";
}

void checkMemoryMerge(comm::Communicator* comm, const vk::Context& ctx) {
  for (uint32_t registers : {1u, 2u}) {
    CompositorOptions o;
    o.registerLists = registers;
    WorldSpec s;
    s.ranks = ranksOf(comm);
    s.seed = 40 + registers;
    s.emptyFraction = 0.05;
    World w = makeWorld(s);
    RankRig rig(comm, ctx, w.width, w.height, o);
    // Twice: the in-memory merge consumes its cursors, the next frame must start afresh.
    for (int frame = 0; frame < 2; ++frame) {
      std::vector<glm::vec4> image = rig.run(w);
      if (rankOf(comm) == 0)
        expectImageNear(image, deepReference(w, o), kTolerance,
                        std::to_string(registers) + " register lists");
    }
  }
}

}  // namespace sm::comp::test
