// shellmarch-bench: the benchmarks, a separate executable so that the shipped `shellmarch` links
// neither the CPU reference renderer nor the peers' file writers. `shellmarch bench ...` runs it;
// it runs `shellmarch render` and `shellmarch generate` beside it for what users would time.
#include <cstdio>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bench/registry.h"
#include "cli/command_words.h"
#include "cli/program.h"

int main(int argc, char** argv) {
  CLI::App app{
      "shellmarch bench: benchmarks that print a table and write JSON "
      "(docs/BENCHMARKS.md)"};
  sm::app::setUpProgram(app);
  for (const sm::app::bench::BenchCommand& c : sm::app::bench::benchCommands())
    c.configure(*app.add_subcommand(c.name, c.description));
  // For `shellmarch completion bash`, which completes `shellmarch bench ...` from these.
  if (argc == 2 && std::strcmp(argv[1], "--completion-words") == 0) {
    std::vector<sm::app::CommandWords> words;
    std::set<std::string> valued;
    sm::app::collectWords(&app, "", words, valued);
    std::fputs(sm::app::encodeWords(words, valued).c_str(), stdout);
    return 0;
  }
  return sm::app::runProgram(app, argc, argv);
}
