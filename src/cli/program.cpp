#include "cli/program.h"

#include <malloc.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <thread>

#include "cli/cli_checks.h"
#include "cli/commands.h"
#include "common/error.h"
#include "common/log.h"
#include "common/parallel.h"
#include "common/progress.h"

namespace {

// Exit statuses: 0 done, 1 an error (bad input, a failed device, a failed rank), 2 a command line
// the option parser refused (as the README says).
constexpr int kUsageError = 2;

// Under mpiexec every rank parses the same options and fails the same way before MPI starts: rank
// 0 says so at once, and mpiexec, seeing it exit, ends the others. They wait a moment before they
// speak, so that their copies of the line appear only where rank 0 did not fail.
bool isRankZero() {
  for (const char* var : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
    if (const char* rank = std::getenv(var)) return std::string(rank) == "0";
  return true;
}

std::string versionText() {
#ifdef __clang__
  const char* compiler = "";  // __VERSION__ names clang itself
#else
  const char* compiler = "GCC ";
#endif
  return sm::concat("shellmarch ", SHELLMARCH_VERSION, " (", SHELLMARCH_BUILD_TYPE, " build, ",
                    compiler, __VERSION__, ")");
}

// Mesa's CPU driver starts a thread per core in every process unless told otherwise: under
// mpirun, 8 ranks on 16 cores would run 128 threads. It gets this process's share, as the
// readers do (common/parallel.h), unless the user chose a number.
void shareTheNodeWithLavapipe() {
  if (!std::getenv("LP_NUM_THREADS"))
    setenv("LP_NUM_THREADS", std::to_string(sm::hardwareThreads()).c_str(), 0);
}

void printError(const std::string& what) {
  if (!isRankZero()) std::this_thread::sleep_for(std::chrono::seconds(2));
  std::fprintf(stderr, "shellmarch: error: %s\n", what.c_str());
}

}  // namespace

namespace sm::app {

void setUpProgram(CLI::App& app) {
  app.require_subcommand(1);
  app.fallthrough();  // -v, -q and --version after the command too: `render MESH -q`
  app.set_version_flag("--version", versionText(), "Print the version and build, then exit");
  static bool verbose = false, quiet = false;  // read by the callback after parsing
  app.add_flag("-v,--verbose", verbose, "More messages");
  app.add_flag("-q,--quiet", quiet, "Errors only");
  app.parse_complete_callback([&app] {
    refuseEmptyValues(app);
    if (verbose) sm::log::setLevel(sm::log::Level::Info);
    if (quiet) sm::log::setLevel(sm::log::Level::Quiet);
    sm::allowProgress(!quiet && isRankZero());
  });
}

int runProgram(CLI::App& app, int argc, char** argv) {
  // Big arrays (cells, scalars, face keys) are mapped on their own and returned to the system when
  // freed. glibc's default raises this threshold after the first large free, after which freed
  // arrays stay resident and a rank's peak memory is the sum of every stage's arrays instead of
  // the largest live set (docs/BENCHMARKS.md, peak memory).
  mallopt(M_MMAP_THRESHOLD, 128 << 10);
  shareTheNodeWithLavapipe();
  try {
    app.name(argv[0]);
    app.parse(parserArguments(argc, argv));
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::Success& e) {  // a flag that prints and ends the run (view --help-script)
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line like every other error (CLI11's own format adds a second line). Status 2 for every
    // command line the parser refuses, as getopt tools do, not CLI11's per-kind codes (104,
    // 105...).
    printError(sm::printableLine(e.what()) + " (see --help)");
    return kUsageError;
  } catch (const UsageError& e) {  // compare's unreadable or mismatched images
    printError(sm::printableLine(e.what()));
    return kUsageError;
  } catch (const sm::Error& e) {
    // Messages quote names from input files: one printable line on the terminal.
    printError(sm::printableLine(e.what()));
    return 1;
  } catch (const std::bad_alloc&) {
    printError("out of memory");
    return 1;
  } catch (const std::exception& e) {
    printError(sm::printableLine(e.what()));
    return 1;
  }
  // Output redirected to a full disk or a closed pipe: a truncated `info --json` must not look
  // like a complete one.
  std::cout.flush();
  if (std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout) {
    printError("cannot write to standard output");
    return 1;
  }
  return 0;
}

std::string executableDir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw Error("cannot find this executable (/proc/self/exe): ", ec.message());
  std::string path = exe.string();
  const std::string deleted = " (deleted)";
  if (path.ends_with(deleted)) path.resize(path.size() - deleted.size());
  return std::filesystem::path(path).parent_path().string();
}

std::string siblingExecutable(const std::string& name) {
  const std::string path = (std::filesystem::path(executableDir()) / name).string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw Error("'", path, "' is missing (shellmarch and shellmarch-bench are built and installed ",
                "side by side)");
  return path;
}

}  // namespace sm::app
