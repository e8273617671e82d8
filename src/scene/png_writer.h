// PNG encoding. Images are encoded by libpng (smaller files, faster than stb_image_write at the
// level chosen: docs/BENCHMARKS.md, `shellmarch bench png`); the stb encoder is kept only so that
// the benchmark can compare the two on the same pixels.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace sm::scene {

// zlib level 0-9, with libpng's adaptive row filters. On a 1024x1024 render (docs/BENCHMARKS.md,
// "PNG encoding") 4 gives 35% fewer bytes than stb in half its time; 6 (zlib's default) 41% fewer
// in more time than stb, 9 48% fewer in ten times the time.
constexpr int kPngLevel = 4;

// Encodes packed 8-bit pixels (`channels` 3: RGB or 4: RGBA, row 0 at the top) as a PNG.
// Throws sm::Error when the sizes disagree or libpng fails.
std::vector<uint8_t> encodePng(std::span<const uint8_t> pixels, int width, int height, int channels,
                               int level = kPngLevel);
// The same pixels through stb_image_write (the encoder before libpng): benchmark only.
std::vector<uint8_t> encodePngStb(std::span<const uint8_t> pixels, int width, int height,
                                  int channels);

}  // namespace sm::scene
