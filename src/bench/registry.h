// The `shellmarch bench` (shellmarch-bench) subcommands, listed in one place (registry.cpp). A new
// benchmark is one new source file in src/bench defining its register function, plus one line in
// the table in registry.cpp; CMake picks the file up by itself.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace sm::app::bench {

struct BenchCommand {
  std::string name;         // `shellmarch bench NAME`
  std::string description;  // one line for --help
  // Adds the options to the subcommand CLI11 created and sets its callback.
  std::function<void(CLI::App& cmd)> configure;
};

const std::vector<BenchCommand>& benchCommands();

// Defined by each benchmark's own file.
void configurePrepBench(CLI::App& cmd);      // bench_prep.cpp
void configureRenderBench(CLI::App& cmd);    // bench_render.cpp
void configureAccuracyBench(CLI::App& cmd);  // bench_accuracy.cpp
void configureFeatureBench(CLI::App& cmd);   // bench_features.cpp
void configureCountBench(CLI::App& cmd);     // bench_counts.cpp
void configureTracerBench(CLI::App& cmd);    // bench_tracers.cpp
void configurePngBench(CLI::App& cmd);       // bench_png.cpp

}  // namespace sm::app::bench
