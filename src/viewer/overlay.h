// The viewer's overlay: lines of text in the 5x7 bitmap font (scene/bitmap_font.h), drawn on the
// CPU into the 8-bit image just before it is copied to the swapchain (it never reaches screenshots,
// which stay comparable with `shellmarch render`).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace sm::view {

struct OverlayBox {
  int x = 0, y = 0, width = 0, height = 0;  // the darkened box behind the text, in pixels
};

// Where drawOverlay puts `lines` at `scale` (pixels per font dot), clipped to nothing here.
OverlayBox overlayBox(const std::vector<std::string>& lines, int scale);

// Darkens the box and draws the lines in white into an RGBA8 image (row 0 at the top); clips to
// the image.
void drawOverlay(std::vector<uint8_t>& rgba, int width, int height,
                 const std::vector<std::string>& lines, int scale = 2);

}  // namespace sm::view
