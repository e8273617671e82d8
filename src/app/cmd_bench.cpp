// `shellmarch bench SUBCOMMAND`: benchmarks that print a table and write JSON (not timed tests).
// The subcommands are listed in bench/registry.cpp.
#include "app/bench/registry.h"
#include "app/commands.h"

namespace sm::app {

void registerBench(CLI::App& app) {
  CLI::App* bench =
      app.add_subcommand("bench", "Benchmarks: print a table, write JSON (see docs/BENCHMARKS.md)");
  bench->require_subcommand(1);
  for (const bench::BenchCommand& c : bench::benchCommands())
    c.configure(*bench->add_subcommand(c.name, c.description));
}

}  // namespace sm::app
