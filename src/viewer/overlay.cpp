#include "viewer/overlay.h"

#include <algorithm>

#include "scene/bitmap_font.h"

namespace sm::view {
namespace {

constexpr int kAdvance = scene::kGlyphAdvance, kLineAdvance = 9, kMargin = 4;

void darken(std::vector<uint8_t>& rgba, int width, int height, const OverlayBox& b) {
  for (int y = std::max(b.y, 0); y < std::min(b.y + b.height, height); ++y)
    for (int x = std::max(b.x, 0); x < std::min(b.x + b.width, width); ++x)
      for (int c = 0; c < 3; ++c) {
        uint8_t& v = rgba[(size_t(y) * width + x) * 4 + c];
        v = uint8_t(v * 3 / 10);
      }
}

void drawChar(std::vector<uint8_t>& rgba, int width, int height, int x0, int y0, char c,
              int scale) {
  scene::drawText(std::string_view(&c, 1), x0, y0, scale, [&](int x, int y) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    uint8_t* p = &rgba[(size_t(y) * width + x) * 4];
    p[0] = p[1] = p[2] = 255;
  });
}

}  // namespace

OverlayBox overlayBox(const std::vector<std::string>& lines, int scale) {
  size_t longest = 0;
  for (const auto& l : lines) longest = std::max(longest, l.size());
  OverlayBox b;
  b.width = (int(longest) * kAdvance + 2 * kMargin) * scale;
  b.height = (int(lines.size()) * kLineAdvance + 2 * kMargin - 2) * scale;
  return b;
}

void drawOverlay(std::vector<uint8_t>& rgba, int width, int height,
                 const std::vector<std::string>& lines, int scale) {
  if (lines.empty()) return;
  darken(rgba, width, height, overlayBox(lines, scale));
  for (size_t i = 0; i < lines.size(); ++i) {
    const int y = (kMargin + int(i) * kLineAdvance) * scale;
    for (size_t j = 0; j < lines[i].size(); ++j)
      drawChar(rgba, width, height, (kMargin + int(j) * kAdvance) * scale, y, lines[i][j], scale);
  }
}

}  // namespace sm::view
