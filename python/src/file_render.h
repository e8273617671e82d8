// shellmarch.render(PATH, ...): `shellmarch render` in this process, its frames handed back.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace sm::python {

struct Frames {
  int width = 0, height = 0;
  std::vector<std::vector<uint8_t>> rgba;  // per frame, 8-bit RGBA rows as the PNG holds them
};

// Renders `path` with the render options `args` (parseSceneArgs) as one process; each frame is
// composited over the background as `render --out F.png` writes it (scene::toRgba8).
Frames renderFile(const std::string& path, const std::vector<std::string>& args);

}  // namespace sm::python
