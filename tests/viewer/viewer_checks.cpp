#include "viewer_checks.h"

#include <cstdio>

#include <gtest/gtest.h>

namespace sm::test {

void expectCleanRun(const CommandResult& r) {
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("validation error"), std::string::npos) << r.err;
}

scene::Image expectMatchesRender(const std::string& dir, const std::string& mesh,
                                 const nlohmann::json& j, const std::string& shot,
                                 const std::string& tag) {
  const std::string out = dir + "/" + tag + ".png";
  CommandResult r = runCommand(
      shellmarch() + " render " + quote(mesh) + renderArgs(j) + " --out " + quote(out), dir, tag);
  expectCleanRun(r);
  scene::Image view = scene::readPng(shot);
  const scene::ImageError e = scene::compareImages(view, scene::readPng(out));
  std::printf("%s: viewer screenshot vs render: RMSE %.3g, max abs %.3g (8-bit steps %.1f)\n",
              tag.c_str(), e.rmse, e.maxAbs, e.maxAbs * 255);
  EXPECT_LE(e.maxAbs, 1.0 / 255 + 1e-6) << tag;
  return view;
}

std::string headlessView(const std::string& mesh, const char* size) {
  return "env -u DISPLAY -u WAYLAND_DISPLAY " + shellmarch() + " view " + quote(mesh) +
         " --field vortex --size " + size + " --headless --print-camera ";
}

}  // namespace sm::test
