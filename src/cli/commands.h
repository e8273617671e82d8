// Each subcommand of the `shellmarch` tool registers itself on the CLI11 app; its callback does the
// work and throws sm::Error for user errors (printed as one line, exit status 1).
#pragma once

#include <CLI/CLI.hpp>

#include "common/error.h"

namespace sm::app {

// A user error reported like a command line the parser refused: one line, exit status 2. For
// `compare` (and `render --compare`), whose status 1 means images beyond the tolerance, as cmp's
// and diff's does: unreadable images, images of different sizes, unwritable outputs.
class UsageError : public Error {
 public:
  using Error::Error;
};

void registerInfo(CLI::App& app);  // cmd_info.cpp
// What `info --json FILE` prints, on one line (cmd_info.cpp; the Python module's info()).
std::string infoJsonText(const std::string& file);
void registerGenerate(CLI::App& app);    // cmd_generate.cpp
void registerRender(CLI::App& app);      // cmd_render.cpp
void registerBench(CLI::App& app);       // cmd_bench.cpp: runs shellmarch-bench
void registerView(CLI::App& app);        // cmd_view.cpp
void registerDevices(CLI::App& app);     // cmd_devices.cpp
void registerCompare(CLI::App& app);     // cmd_compare.cpp
void registerCompletion(CLI::App& app);  // cmd_completion.cpp: after every other command

}  // namespace sm::app
