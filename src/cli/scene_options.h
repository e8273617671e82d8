// Command-line options that `render` and `view` share: the data, camera, transfer function,
// sampling, fragment lists and device. Values that need parsing are kept as text while CLI11
// parses and turned into the RenderJob's fields afterwards, so errors name the option.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "pipeline/render_options.h"

namespace sm::app {

struct SceneOptionText {
  std::map<std::string, std::string> text;  // option name -> value as given
  std::vector<std::string> clip;            // --clip, once per plane
  bool plain = false;
  bool shading = false;
  bool logScale = false;
  bool parallel = false;
  const CLI::Option* fovy = nullptr;  // given or not: it overrides a --camera file's angle
};

// Registers the shared options on `cmd`, in render's order; `timeHelp` describes --time, whose
// accepted values differ between the commands. `job` and `raw` must outlive the parse.
void addSceneOptions(CLI::App* cmd, RenderJob& job, SceneOptionText& raw,
                     const std::string& timeHelp);

// Sorts every option of `cmd` into the help's groups (data, camera, transfer function, time,
// output, parallel, device), by name. Throws (an invariant) for an option no group names, so a
// new option cannot land in CLI11's catch-all "OPTIONS" unseen.
void groupSceneOptions(CLI::App* cmd);

// Parses the text options into `job`; throws sm::Error naming the option.
void applySceneOptions(SceneOptionText& raw, RenderJob& job);

}  // namespace sm::app
