// Each subcommand of the `shellmarch` tool registers itself on the CLI11 app; its callback does the
// work and throws sm::Error for user errors (printed as one line, exit status 1).
#pragma once

#include <CLI/CLI.hpp>

namespace sm::app {

void registerInfo(CLI::App& app);      // cmd_info.cpp
void registerGenerate(CLI::App& app);  // cmd_generate.cpp
void registerRender(CLI::App& app);    // cmd_render.cpp
void registerBench(CLI::App& app);     // cmd_bench.cpp (subcommands: bench/registry.cpp)
void registerView(CLI::App& app);      // cmd_view.cpp
void registerDevices(CLI::App& app);   // cmd_devices.cpp

}  // namespace sm::app
