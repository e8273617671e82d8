// Option checks CLI11 runs while parsing, before any work: an empty name ("--field ''" would
// otherwise mean "the default"), and a file to write whose folder exists and which is not a
// folder (a bad --json found only after a benchmark ran for minutes). Light on purpose: the
// commands' option tables include it.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace sm::app {

CLI::Validator nonEmptyName();
CLI::Validator writableFile();

// Marks an option whose empty value means something (bench --exact "": no such runs).
CLI::Option* allowEmptyValue(CLI::Option* option);

// The arguments after the program's name, reversed as CLI::App::parse takes them, with "--NAME="
// split into "--NAME" and "": CLI11 would otherwise give the next argument to that option and
// report that one as unexpected, where refuseEmptyValues names the option.
std::vector<std::string> parserArguments(int argc, const char* const* argv);

// Refuses an empty value ("--range ''", "--step=") of every option of the subcommands given that
// takes one, but those marked above: an unset shell variable must not quietly mean the default.
void refuseEmptyValues(const CLI::App& app);

}  // namespace sm::app
