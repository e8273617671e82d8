// Running the shellmarch tool from tests: commands with their output captured, the test mesh,
// JSON from --print-camera, and Xvfb's framebuffer (Xvfb -fbdir writes it as an XWD file).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/image.h"

namespace sm::test {

struct CommandResult {
  int status = -1;  // exit status (-1: did not exit normally)
  std::string out, err;
};

std::string quote(const std::string& s);
// Writes `text` (a script, say) to dir/name and returns the path.
std::string writeFile(const std::string& dir, const std::string& name, const std::string& text);
// Runs `command` through the shell, stdout and stderr to files in `dir` named after `tag`.
CommandResult runCommand(const std::string& command, const std::string& dir,
                         const std::string& tag);

std::string shellmarch();  // the tool under test, quoted
// xvfb-run -a with these X server arguments (a 24-bit screen: Vulkan presents no 8-bit visual).
std::string xvfbRun(const std::string& serverArgs = "-screen 0 640x480x24");
std::string mpiexec();  // mpiexec, quoted

// A small .pvtu (tetrahedralised cube, 4 clusters, 3 time steps, fields linear/shock/vortex).
std::string generateTestMesh(const std::string& dir);

// The last line of `out` that parses as a JSON object.
nlohmann::json lastJson(const std::string& out);
// `render` arguments from a --print-camera line, quoted, space-separated.
std::string renderArgs(const nlohmann::json& j);

// Xvfb's screen from its -fbdir file, as an opaque 8-bit image.
scene::Image readXwd(const std::string& path);

// Pixels that differ from `background` by more than 2/255 in some channel.
size_t pixelsUnlike(const scene::Image& img, const glm::vec3& background);

}  // namespace sm::test
