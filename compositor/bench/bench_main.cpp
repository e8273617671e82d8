// shellmarch_bench_compositor run|sweep|replay: see bench.h and docs/COMPOSITOR.md.
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include <CLI/CLI.hpp>

#include "bench.h"
#include "compositor/exchange_plan.h"

#ifndef SHELLMARCH_MPIEXEC
#define SHELLMARCH_MPIEXEC "mpiexec"
#endif

namespace sm::comp::bench {

int sweepBenchmark(const SweepOptions& o, const std::string& self) {
  nlohmann::json rows = nlohmann::json::array();
  std::string sizes;
  for (int s : o.run.sizes) sizes += (sizes.empty() ? "" : ",") + std::to_string(s);
  std::string ownerships;
  for (const std::string& w : o.run.ownerships) ownerships += (ownerships.empty() ? "" : ",") + w;
  for (int n = 1; n <= o.maxRanks; ++n) {
    const std::string part =
        o.run.json.empty() ? "/tmp/shellmarch_bench_compositor.json" : o.run.json + ".part";
    const std::string cmd = o.mpiexec + " -n " + std::to_string(n) + " --oversubscribe " + self +
                            " run --sizes " + sizes + " --frames " + std::to_string(o.run.frames) +
                            " --depth-blocks " + std::to_string(o.run.depthBlocks) +
                            " --ownerships " + ownerships + " --json " + part + " > /dev/null";
    std::fprintf(stderr, "%s\n", cmd.c_str());
    if (std::system(cmd.c_str()) != 0) {
      std::fprintf(stderr, "sweep: %d ranks failed\n", n);
      return 1;
    }
    nlohmann::json part_rows = nlohmann::json::parse(std::ifstream(part));
    for (auto& r : part_rows) rows.push_back(r);
    std::remove(part.c_str());
  }
  printRunTable(rows);
  if (!o.run.json.empty()) {
    std::ofstream(o.run.json) << rows.dump(1) << "\n";
    std::printf("wrote %s\n", o.run.json.c_str());
  }
  return 0;
}

}  // namespace sm::comp::bench

int main(int argc, char** argv) {
  using namespace sm::comp::bench;
  CLI::App app{"Deep compositing benchmark: bytes per frame and time against rank count"};
  app.require_subcommand(1);
  RunOptions run;
  auto addRunOptions = [&](CLI::App* c) {
    c->add_option("--sizes", run.sizes, "square image sizes")->delimiter(',');
    c->add_option("--frames", run.frames, "timed frames per configuration")
        ->check(CLI::PositiveNumber);
    c->add_option("--depth-blocks", run.depthBlocks, "synthetic partition blocks per axis")
        ->check(CLI::PositiveNumber);
    c->add_option("--json", run.json, "write the rows as JSON");
    c->add_option("--ownerships", run.ownerships,
                  "pixel ownerships to time: interleaved, ranges or both")
        ->delimiter(',')
        ->check([](const std::string& name) {
          try {
            sm::comp::parseOwnership(name);
            return std::string();
          } catch (const std::invalid_argument& e) {
            return std::string(e.what());
          }
        });
  };
  CLI::App* runCmd = app.add_subcommand("run", "one rank count (under mpiexec)");
  addRunOptions(runCmd);
  runCmd->add_option("--dump-counts", run.dumpCounts,
                     "write per-rank counts of the largest image (for replay --dump)");
  SweepOptions sweep;
  sweep.mpiexec = SHELLMARCH_MPIEXEC;
  CLI::App* sweepCmd = app.add_subcommand("sweep", "run under mpiexec for 1 .. N ranks");
  addRunOptions(sweepCmd);
  sweepCmd->add_option("--max-ranks", sweep.maxRanks)->check(CLI::Range(1, 64));
  sweepCmd->add_option("--mpiexec", sweep.mpiexec);
  ReplayOptions replay;
  CLI::App* replayCmd = app.add_subcommand("replay", "exchange arithmetic without MPI");
  replayCmd->add_option("--ranks", replay.ranks, "rank counts")->delimiter(',');
  replayCmd->add_option("--width", replay.width)->check(CLI::PositiveNumber);
  replayCmd->add_option("--height", replay.height)->check(CLI::PositiveNumber);
  replayCmd->add_option("--depth-blocks", replay.depthBlocks, "0: scaled with the rank count");
  replayCmd->add_option("--counter-bits", replay.counterBits, "force 2, 4, 8 or 32 (0: chosen)");
  replayCmd->add_option("--dump", replay.dump, "count dump (format: docs/COMPOSITOR.md)");
  replayCmd->add_option("--json", replay.json);
  CLI11_PARSE(app, argc, argv);
  try {
    if (*runCmd) return runBenchmark(run);
    if (*sweepCmd) {
      sweep.run = run;
      return sweepBenchmark(sweep, argv[0]);
    }
    return replayBenchmark(replay);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "shellmarch_bench_compositor: %s\n", e.what());
    return 1;
  }
}
