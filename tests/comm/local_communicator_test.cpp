// In-process ranks: threads of one process that talk as MPI ranks would.
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

#include "comm/local_communicator.h"

namespace sm::comm {
namespace {

TEST(LocalCommunicator, CollectivesMoveWhatEachRankPosted) {
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

TEST(LocalCommunicator, MismatchedSizesFailOnTheReceiverInsteadOfCorruptingMemory) {
  EXPECT_THROW(runLocalRanks(2,
                             [](Communicator& c) {
                               uint8_t send[8] = {}, recv[8] = {};
                               std::vector<uint64_t> sb = {2, 2}, off = {0, 4};
                               std::vector<uint64_t> rb = {2, uint64_t(c.rank() == 0 ? 3 : 2)};
                               c.alltoallv(send, sb, off, recv, rb, off);
                             }),
               CommError);
}

TEST(LocalCommunicator, AbortReleasesRanksWaitingInACollective) {
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

TEST(LocalCommunicator, RunOrAbortTurnsAnErrorIntoAnAbortOfAllRanks) {
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
TEST(LocalCommunicator, ARankThatCannotStartEndsTheOthersWithAnError) {
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

}  // namespace
}  // namespace sm::comm
