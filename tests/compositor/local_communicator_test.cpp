// In-process ranks, count dumps and comparison images: the host pieces the compositor and its
// benchmark rely on.
#include <gtest/gtest.h>
#include <pthread.h>
#include <sys/resource.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <string>

#include "compositor/count_dump.h"
#include "compositor/image_compare.h"
#include "compositor/local_communicator.h"

namespace sm::comp {
namespace {

TEST(CompositorLocalCommunicator, CollectivesMoveWhatEachRankPosted) {
  runLocalRanks(4, [](Communicator& c) {
    const int me = c.rank(), n = c.size();
    EXPECT_EQ(c.allreduceMax(uint64_t(10 + me)), 13u);
    EXPECT_EQ(c.allreduceSum(uint64_t(1) << 40), uint64_t(4) << 40);
    // Rank s sends s + d + 1 bytes of value 16 s + d to rank d, packed after each other.
    std::vector<uint64_t> sb(4), so(4), rb(4), ro(4);
    std::vector<uint8_t> send, recv;
    for (int d = 0; d < n; ++d) {
      so[d] = send.size();
      sb[d] = uint64_t(me + d + 1);
      send.insert(send.end(), sb[d], uint8_t(16 * me + d));
      rb[d] = uint64_t(d + me + 1);
      ro[d] = d == 0 ? 0 : ro[d - 1] + rb[d - 1];
    }
    recv.resize(ro[3] + rb[3]);
    c.alltoallv(send.data(), sb, so, recv.data(), rb, ro);
    for (int s = 0; s < n; ++s)
      for (uint64_t i = 0; i < rb[s]; ++i) ASSERT_EQ(recv[ro[s] + i], uint8_t(16 * s + me));
    uint32_t mine = 100u + uint32_t(me), all[4] = {};
    std::vector<uint64_t> gb(4, 4), go = {12, 8, 4, 0};  // root stores them in reverse
    c.gatherv(&mine, 4, all, gb, go, 0);
    if (me == 0) {
      EXPECT_EQ(std::vector<uint32_t>(all, all + 4), (std::vector<uint32_t>{103, 102, 101, 100}));
    }
    uint64_t v = me == 2 ? 42 : 0;
    c.broadcast(&v, sizeof v, 2);
    EXPECT_EQ(v, 42u);
    c.barrier();
  });
}

TEST(CompositorLocalCommunicator, MismatchedSizesFailOnTheReceiverInsteadOfCorruptingMemory) {
  EXPECT_THROW(runLocalRanks(2,
                             [](Communicator& c) {
                               uint8_t send[8] = {}, recv[8] = {};
                               std::vector<uint64_t> sb = {2, 2}, off = {0, 4};
                               std::vector<uint64_t> rb = {2, uint64_t(c.rank() == 0 ? 3 : 2)};
                               c.alltoallv(send, sb, off, recv, rb, off);
                             }),
               CommError);
}

TEST(CompositorLocalCommunicator, AbortReleasesRanksWaitingInACollective) {
  std::atomic<int> aborted = 0;
  try {
    runLocalRanks(3, [&](Communicator& c) {
      if (c.rank() == 2) c.abort("disk full");
      try {
        c.barrier();
      } catch (const CommAborted& e) {
        EXPECT_NE(std::string(e.what()).find("rank 2: disk full"), std::string::npos);
        ++aborted;
        throw;
      }
    });
    FAIL() << "expected CommAborted";
  } catch (const CommAborted& e) {
    EXPECT_NE(std::string(e.what()).find("disk full"), std::string::npos);
  }
  EXPECT_EQ(aborted, 2);
}

TEST(CompositorLocalCommunicator, RunOrAbortTurnsAnErrorIntoAnAbortOfAllRanks) {
  try {
    runLocalRanks(2, [](Communicator& c) {
      runOrAbort(c, [&] {
        if (c.rank() == 0) throw std::runtime_error("bad input");
        c.barrier();
      });
    });
    FAIL() << "expected CommAborted";
  } catch (const CommAborted& e) {
    EXPECT_EQ(std::string(e.what()), "rank 0: bad input");
  }
}

// When a rank's thread cannot start, the ranks that did start leave their collectives and the
// caller gets a CommError instead of std::terminate (a joinable std::thread destroyed). Run in a
// child process whose address space is capped so that thread stacks (8 MiB each) soon run out.
TEST(CompositorLocalCommunicator, ARankThatCannotStartEndsTheOthersWithAnError) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "the sanitizers' own mappings do not survive an address-space cap";
#endif
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        struct rlimit cap = {};
        getrlimit(RLIMIT_AS, &cap);
        std::ifstream status("/proc/self/status");
        std::string line;
        uint64_t kib = 0;
        while (std::getline(status, line))
          if (line.rfind("VmSize:", 0) == 0) kib = std::stoull(line.substr(7));
        // Room for a few threads' stacks, not for 256 of them.
        pthread_attr_t attr;
        size_t stack = 0;
        if (pthread_getattr_default_np(&attr) != 0 || pthread_attr_getstacksize(&attr, &stack) != 0)
          std::_Exit(6);
        cap.rlim_cur = kib * 1024 + 6 * stack;
        if (setrlimit(RLIMIT_AS, &cap) != 0) std::_Exit(7);
        try {
          runLocalRanks(256, [](Communicator& c) { c.barrier(); });
        } catch (const CommAborted&) {
          std::_Exit(3);
        } catch (const CommError& e) {
          std::fprintf(stderr, "%s\n", e.what());
          std::_Exit(std::string(e.what()).find("cannot start rank") != std::string::npos ? 0 : 4);
        }
        std::_Exit(5);  // every thread started: the cap did not bite
      },
      ::testing::ExitedWithCode(0), "local ranks: cannot start rank [0-9]+ of 256");
}

std::string tempPath(const char* name) {
  return ::testing::TempDir() + name;
}

TEST(CompositorCountDump, RoundTripsRanksInAnyOrder) {
  const std::string path = tempPath("counts.smfc");
  std::vector<std::vector<uint32_t>> counts = {{1, 2, 3, 4, 5, 6}, {0, 0, 7, 0, 0, 8}};
  CountDumpWriter w(path, 3, 2, 2);
  for (const auto& c : counts) w.append(c);
  w.close();
  CountDumpReader r(path);
  EXPECT_EQ(r.width(), 3u);
  EXPECT_EQ(r.height(), 2u);
  EXPECT_EQ(r.ranks(), 2u);
  std::vector<uint32_t> got;
  r.read(1, got);
  EXPECT_EQ(got, counts[1]);
  r.read(0, got);
  EXPECT_EQ(got, counts[0]);
  EXPECT_THROW(r.read(2, got), std::runtime_error);
  std::remove(path.c_str());
}

TEST(CompositorCountDump, RejectsWrongSizesAndForeignFiles) {
  const std::string path = tempPath("short.smfc");
  std::remove(path.c_str());
  {
    CountDumpWriter w(path, 2, 2, 2);
    EXPECT_THROW(w.append(std::vector<uint32_t>(3)), std::runtime_error);
    w.append(std::vector<uint32_t>(4));
    EXPECT_THROW(w.close(), std::runtime_error) << "one rank missing";
  }
  // An unfinished dump never takes the name of a whole one, nor stays behind as a part.
  EXPECT_FALSE(std::ifstream(path).good());
  EXPECT_FALSE(std::ifstream(path + ".part").good());
  EXPECT_THROW(CountDumpWriter(path, 0, 2, 1), std::runtime_error) << "empty image";
  EXPECT_THROW(CountDumpWriter(path, 2, 2, 0), std::runtime_error) << "no ranks";
  EXPECT_FALSE(std::ifstream(path + ".part").good()) << "a refused dump leaves no part behind";
  {  // A dump cut short on disk (a full disk, a copy interrupted) is caught by the reader.
    CountDumpWriter w(path, 2, 2, 2);
    w.append(std::vector<uint32_t>(4));
    w.append(std::vector<uint32_t>(4));
    w.close();
  }
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 4);
  EXPECT_THROW(CountDumpReader{path}, std::runtime_error) << "truncated";
  std::ofstream(path) << "P6 not a dump";
  EXPECT_THROW(CountDumpReader{path}, std::runtime_error);
  std::remove(path.c_str());
}

TEST(CompositorImageCompare, DifferenceAndHeatmap) {
  std::vector<glm::vec4> a = {{0, 0, 0, 0}, {1, 0, 0, 1}}, b = {{0, 0, 0, 0}, {0, 0, 0, 1}};
  std::vector<float> d = l2Difference(a, b);
  EXPECT_EQ(d, (std::vector<float>{0.0f, 1.0f}));
  std::vector<glm::vec4> h = heatmap(std::span<const float>(d));
  EXPECT_EQ(h[0], glm::vec4(0, 0, 0, 1));
  EXPECT_GT(h[1].r + h[1].g + h[1].b, 2.5f) << "the maximum maps to the bright end";
  std::vector<uint32_t> counts = {0, 5, 10};
  std::vector<glm::vec4> hc = heatmap(std::span<const uint32_t>(counts), 5.0f);
  EXPECT_EQ(hc[1], hc[2]) << "values above the maximum saturate";
  EXPECT_THROW(l2Difference(a, std::vector<glm::vec4>(1)), std::invalid_argument);
  EXPECT_EQ(sumCounts({{1, 2}, {3, 4}}), (std::vector<uint32_t>{4, 6}));
  EXPECT_THROW(sumCounts({{1, 2}, {3}}), std::invalid_argument);
}

}  // namespace
}  // namespace sm::comp
