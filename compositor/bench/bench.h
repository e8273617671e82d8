// shellmarch_bench_compositor: what deep compositing costs (bytes per frame and time against rank
// count, per fragment and counter encoding) and, by replay, what it would send at rank counts this
// machine cannot run. A benchmark, not a test: it prints a table and writes JSON.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sm::comp::bench {

struct RunOptions {
  std::vector<int> sizes = {512, 1024};  // square images
  int frames = 3;                        // timed frames per configuration (after one warm-up)
  uint32_t depthBlocks = 12;             // synthetic partition: blocks along each axis
  std::string json;                      // output file ("" = none)
  std::string dumpCounts;                // write the per-rank counts of the largest image here
  std::vector<std::string> ownerships = {"interleaved"};  // pixel ownerships to time, each a row
};

struct ReplayOptions {
  std::vector<int> ranks = {72, 552};
  int width = 1024, height = 1024;
  uint32_t depthBlocks = 0;  // 0: scaled with the rank count
  uint32_t counterBits = 0;  // 0: from the longest list, as the compositor chooses
  std::string dump;          // replay these counts instead of the synthetic scene
  std::string json;
};

struct SweepOptions {
  int maxRanks = 8;
  std::string mpiexec;
  RunOptions run;
};

// Under mpiexec (or alone for one rank): every configuration on the ranks of MPI_COMM_WORLD.
int runBenchmark(const RunOptions& o);
int replayBenchmark(const ReplayOptions& o);
// Runs runBenchmark under mpiexec for 1 .. maxRanks processes and prints one merged table.
int sweepBenchmark(const SweepOptions& o, const std::string& self);

// Rows of the run table (one per ranks, size, encoding, counter width).
void printRunTable(const nlohmann::json& rows);

}  // namespace sm::comp::bench
