// The Python keyword arguments of a render, as the Python side spells them on `shellmarch render`'s
// command line, parsed by the command's own option registration: one parser, one set of checks
// and messages for the CLI and the module.
#pragma once

#include <string>
#include <vector>

#include "pipeline/render_options.h"

namespace sm::python {

// Parses `shellmarch render MESH ARGS...` (the shared scene options only; --out and the other
// options of files are not taken). Throws CLI::ParseError or sm::Error naming the option.
app::RenderJob parseSceneArgs(const std::string& mesh, const std::vector<std::string>& args);

}  // namespace sm::python
