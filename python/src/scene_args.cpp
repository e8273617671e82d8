#include "scene_args.h"

#include <algorithm>

#include <CLI/CLI.hpp>

#include "cli/cli_checks.h"
#include "cli/scene_options.h"

namespace sm::python {

app::RenderJob parseSceneArgs(const std::string& mesh, const std::vector<std::string>& args) {
  CLI::App app{"shellmarch"};
  app.require_subcommand(1);
  CLI::App* cmd = app.add_subcommand("render", "Render a mesh");
  app::RenderJob job;
  app::SceneOptionText raw;
  addSceneOptions(cmd, job, raw, "Time step K, or t=TIME: the step nearest that time value");
  std::vector<std::string> argv = {"render", mesh};
  argv.insert(argv.end(), args.begin(), args.end());
  std::reverse(argv.begin(), argv.end());  // CLI::App::parse takes them reversed
  app.parse(argv);
  app::refuseEmptyValues(app);
  applySceneOptions(raw, job);
  return job;
}

}  // namespace sm::python
