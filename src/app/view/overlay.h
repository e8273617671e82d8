// The viewer's overlay: lines of text in a 5x7 bitmap font, drawn on the CPU into the 8-bit image
// just before it is copied to the swapchain (it never reaches screenshots, which stay comparable
// with `shellmarch render`). Letters show in upper case.
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

// The 7 rows of a character's 5-dot-wide glyph (bit 4 = leftmost); '?' for characters the font
// lacks, lower case mapped to upper case.
const uint8_t* glyph(char c);

}  // namespace sm::view
