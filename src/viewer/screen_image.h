// Small helpers for the images the viewer shows and saves.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

namespace sm::view {

// FILE.png -> FILE_0012.png (frame 12), for the screenshot key; "" names shellmarch-view.png.
std::string numberedPath(const std::string& base, uint32_t frame);

// A reduced frame, enlarged into `out` (whose storage is reused) to the window's size by
// repeating each pixel.
void enlarge(const std::vector<glm::vec4>& small, int smallWidth, int smallHeight, int width,
             int height, std::vector<glm::vec4>& out);

}  // namespace sm::view
