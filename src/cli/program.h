// What both executables (`shellmarch` and `shellmarch-bench`) do around their commands: the global
// flags (-v, -q, --version), lavapipe's share of the cores, and errors as one line with exit
// status 1 (a failed command) or 2 (a command line the parser refused), as the README says.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace sm::app {

// Adds the global flags to `app`; before its commands are added, which inherit its settings (-v
// and -q after the command name too).
void setUpProgram(CLI::App& app);
// Parses argv and runs the chosen command; returns the exit status. Usage lines name the program
// as argv[0] does.
int runProgram(CLI::App& app, int argc, char** argv);

// The directory of this executable (/proc/self/exe), where its sibling executables are installed
// and built. A binary replaced while it runs (a rebuild during a long benchmark) still names the
// new file, not "PATH (deleted)".
std::string executableDir();
// `name` (shellmarch or shellmarch-bench) beside this executable; throws naming the path when it
// is missing.
std::string siblingExecutable(const std::string& name);

}  // namespace sm::app
