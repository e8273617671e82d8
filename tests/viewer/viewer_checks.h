// Checks the viewer tests share: a clean run, a screenshot against `shellmarch render` with the
// report's arguments, and the headless session's command prefix.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "scene/image.h"
#include "viewer_runner.h"

namespace sm::test {

// Exit status 0 and no validation error on stderr.
void expectCleanRun(const CommandResult& r);

// The screenshot equals `shellmarch render` at the viewer's final camera, step and settings (the
// report's render_args); `tag` names the files. Returns the screenshot.
scene::Image expectMatchesRender(const std::string& dir, const std::string& mesh,
                                 const nlohmann::json& j, const std::string& shot,
                                 const std::string& tag = "render");

// `shellmarch view MESH --field vortex --size WxH --headless --print-camera `, without a display:
// the start of every headless session.
std::string headlessView(const std::string& mesh, const char* size);

}  // namespace sm::test
