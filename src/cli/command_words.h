// The words a shell completes for a CLI11 command tree: every command path with its options and
// subcommands, and which options take a value. `shellmarch completion` writes them into a bash
// script; shellmarch-bench hands its own to it as text (--completion-words), since `bench` runs
// that executable.
#pragma once

#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace sm::app {

struct CommandWords {
  std::string path;  // "" (the program), "render", "bench render"
  std::vector<std::string> options, subcommands;
};

// Every command path under `cmd` (hidden options and commands left out) with its options and
// subcommands; the options that take a value go to `valued`.
void collectWords(const CLI::App* cmd, const std::string& path, std::vector<CommandWords>& out,
                  std::set<std::string>& valued);

// The words separated by single spaces.
std::string joinWords(const std::vector<std::string>& words);

// One line per command: path, options, subcommands and valued options, tab-separated, each a
// space-separated list; decodeWords reads them back, adding the valued options to `valued`.
std::string encodeWords(const std::vector<CommandWords>& words,
                        const std::set<std::string>& valued);
std::vector<CommandWords> decodeWords(const std::string& text, std::set<std::string>& valued);

}  // namespace sm::app
