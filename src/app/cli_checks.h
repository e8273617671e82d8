// Option checks CLI11 runs while parsing, before any work: an empty name ("--field ''" would
// otherwise mean "the default"), and a file to write whose folder exists and which is not a
// folder (a bad --json found only after a benchmark ran for minutes). Light on purpose: the
// commands' option tables include it.
#pragma once

#include <CLI/CLI.hpp>

namespace sm::app {

CLI::Validator nonEmptyName();
CLI::Validator writableFile();

}  // namespace sm::app
