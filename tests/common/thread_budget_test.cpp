// How many threads a process takes: OMP_NUM_THREADS, the affinity mask, and the ranks sharing a
// node (common/parallel.h).
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/parallel.h"

namespace sm {
namespace {

// threadBudget with these variables set and no others, on a node of `nodeCpus` cores.
ThreadBudget budgetWith(const std::map<std::string, std::string>& vars, unsigned maskCpus,
                        unsigned nodeCpus = 16) {
  return threadBudget(
      [&](const char* name) -> const char* {
        auto it = vars.find(name);
        return it == vars.end() ? nullptr : it->second.c_str();
      },
      maskCpus, nodeCpus);
}

TEST(ThreadBudget, OmpNumThreadsWins) {
  EXPECT_EQ(budgetWith({{"OMP_NUM_THREADS", "3"}}, 16).threads, 3u);
  EXPECT_EQ(budgetWith({{"OMP_NUM_THREADS", "3"}, {"OMPI_COMM_WORLD_LOCAL_SIZE", "8"}}, 1).threads,
            3u);
  // OpenMP's nested form: the outer level's count.
  EXPECT_EQ(budgetWith({{"OMP_NUM_THREADS", "5,2"}}, 1).threads, 5u);
  EXPECT_EQ(budgetWith({{"OMP_NUM_THREADS", "5,2"}}, 1).reason, "OMP_NUM_THREADS");
}

TEST(ThreadBudget, AMalformedOmpNumThreadsIsIgnored) {
  for (const char* bad : {"", "0", "-2", "four", "3x", "99999999999999999999"}) {
    const ThreadBudget b = budgetWith({{"OMP_NUM_THREADS", bad}}, 1);
    EXPECT_EQ(b.threads, 1u) << bad;
    EXPECT_EQ(b.reason, "affinity mask") << bad;
  }
}

TEST(ThreadBudget, TheAffinityMaskBoundsOneProcess) {
  EXPECT_EQ(budgetWith({}, 1).threads, 1u);
  EXPECT_EQ(budgetWith({}, 6).threads, 6u);
  EXPECT_EQ(budgetWith({}, 16).threads, 16u);
  // This process, as it runs: its own mask, at most the machine.
  EXPECT_GE(threadBudget().threads, 1u);
  EXPECT_LE(threadBudget().threads, machineThreads());
}

TEST(ThreadBudget, RanksOnOneNodeShareItsCores) {
  // Unbound ranks (each mask the whole 16-core node): the cores divided among them, at least 1.
  const ThreadBudget shared = budgetWith({{"OMPI_COMM_WORLD_LOCAL_SIZE", "2"}}, 16);
  EXPECT_EQ(shared.threads, 8u);
  EXPECT_EQ(shared.reason, "cores / 2 ranks on this node");
  EXPECT_EQ(budgetWith({{"MPI_LOCALNRANKS", "3"}}, 16).threads, 5u);
  EXPECT_EQ(budgetWith({{"SLURM_NTASKS_PER_NODE", "1000"}}, 16).threads, 1u);
  // Open MPI's variable is read first.
  EXPECT_EQ(budgetWith({{"OMPI_COMM_WORLD_LOCAL_SIZE", "4"}, {"MPI_LOCALNRANKS", "2"}}, 16).threads,
            4u);
  // Bound to one core each: the mask already divides the node.
  EXPECT_EQ(budgetWith({{"OMPI_COMM_WORLD_LOCAL_SIZE", "16"}}, 1).threads, 1u);
  EXPECT_EQ(budgetWith({{"OMPI_COMM_WORLD_LOCAL_SIZE", "4"}}, 4).reason, "affinity mask");
  // One rank on the node: its mask, whatever runs elsewhere.
  EXPECT_EQ(budgetWith({{"OMPI_COMM_WORLD_LOCAL_SIZE", "1"}}, 16).threads, 16u);
}

TEST(ThreadBudget, ASocketBoundRankTakesItsShareOfTheNode) {
  // 16 cores, 8 ranks bound to a socket of 8 cores each: 2 threads each, not 8.
  const ThreadBudget b = budgetWith({{"OMPI_COMM_WORLD_LOCAL_SIZE", "8"}}, 8);
  EXPECT_EQ(b.threads, 2u);
  EXPECT_EQ(b.reason, "cores / 8 ranks on this node");
}

TEST(ParallelFor, RunsEveryIndexOnceWithTheBudget) {
  std::vector<int> hits(10000, 0);
  parallelFor(int64_t(hits.size()), [&](int64_t b, int64_t e) {
    for (int64_t i = b; i < e; ++i) ++hits[size_t(i)];
  });
  for (int h : hits) ASSERT_EQ(h, 1);
}

}  // namespace
}  // namespace sm
