// `shellmarch`: the command-line tool. Its commands live in the shellmarch_cli library (the
// viewer's in shellmarch_viewer); `bench` runs the separate shellmarch-bench executable.
#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "cli/program.h"

int main(int argc, char** argv) {
  CLI::App app{
      "shellmarch: direct volume rendering of unstructured meshes, data-parallel over MPI"};
  sm::app::setUpProgram(app);
  sm::app::registerInfo(app);
  sm::app::registerGenerate(app);
  sm::app::registerRender(app);
  sm::app::registerBench(app);
  sm::app::registerView(app);
  sm::app::registerDevices(app);
  sm::app::registerCompare(app);
  sm::app::registerCompletion(app);
  return sm::app::runProgram(app, argc, argv);
}
