// A 5x7 bitmap font for text drawn into images on the CPU: the viewer's overlay, the colour legend
// of `render --legend`, the benchmark's plots. Printable ASCII, upper and lower case.
#pragma once

#include <cstdint>
#include <functional>
#include <string_view>

namespace sm::scene {

constexpr int kGlyphWidth = 5, kGlyphHeight = 7;
constexpr int kGlyphAdvance = 6;  // a character's width and the gap after it, in font dots

// The 7 rows of a character's glyph (bit 4 = leftmost dot); '?' for characters outside printable
// ASCII (control characters, UTF-8 bytes).
const uint8_t* glyph(char c);
// Pixels from the first dot of `text` to its last, at `scale` pixels per dot.
int textWidth(std::string_view text, int scale);
// Calls dot(x, y) for every pixel of `text` with its top-left corner at (x, y); no clipping.
void drawText(std::string_view text, int x, int y, int scale,
              const std::function<void(int x, int y)>& dot);

}  // namespace sm::scene
