// `shellmarch bench SUBCOMMAND`: runs the shellmarch-bench executable installed beside this one
// (benchmarks link the CPU reference renderer and the peers' file writers, which the shipped tool
// does not). Everything after `bench`, --help included, goes to it; -v and -q given before
// `bench` go with it.
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/program.h"
#include "common/log.h"

namespace sm::app {

namespace {

[[noreturn]] void runBench(const std::vector<std::string>& args) {
  const std::string exe = siblingExecutable("shellmarch-bench");
  std::vector<std::string> words = {"shellmarch bench"};
  if (log::level() == log::Level::Info) words.push_back("--verbose");
  if (log::level() == log::Level::Quiet) words.push_back("--quiet");
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  execv(exe.c_str(), argv.data());
  throw Error("bench: cannot run '", exe, "': ", std::strerror(errno));
}

}  // namespace

void registerBench(CLI::App& app) {
  CLI::App* bench = app.add_subcommand(
      "bench", "Benchmarks: print a table, write JSON (see docs/BENCHMARKS.md; shellmarch-bench)");
  bench->prefix_command();
  bench->fallthrough(false);  // its arguments are shellmarch-bench's, not this program's
  bench->set_help_flag();     // `bench --help` and `bench render --help` are shellmarch-bench's
  bench->allow_extras();
  bench->callback([bench] { runBench(bench->remaining()); });
}

}  // namespace sm::app
