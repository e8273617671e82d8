// Float RGBA images (premultiplied colour + opacity, row 0 at the top), PNG I/O and the error
// metrics that image tests and accuracy benchmarks report.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace sm::scene {

struct Image {
  int width = 0, height = 0;
  std::vector<glm::vec4> pixels;
  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(size_t(w) * h, glm::vec4(0.0f)) {}
  glm::vec4& at(int x, int y) { return pixels[size_t(y) * width + x]; }
  const glm::vec4& at(int x, int y) const { return pixels[size_t(y) * width + x]; }
};

// What a frame lies over in an 8-bit image: a colour, or none (std::nullopt: transparent, the
// file keeps the frame's alpha; `--background transparent`).
using Background = std::optional<glm::vec3>;

// The 8-bit RGBA bytes (row 0 first, 4 per pixel) that a PNG of `img` holds: the premultiplied
// colour composited over `background` with alpha 255, or with no background the colour
// un-premultiplied (colour / alpha; 0 where alpha is 0) and the alpha. Every PNG writer (files,
// the in-situ and Python APIs) goes through this, so that they agree byte for byte.
std::vector<uint8_t> toRgba8(const Image& img, const Background& background);
// Writes toRgba8(img, background) as a PNG, atomically (a temporary name, then renamed): RGB over a
// background, RGBA without one. Encoded by libpng (scene/png_writer.h).
void writePng(const std::string& path, const Image& img, const Background& background);
// Writes the image's colour with alpha as an 8-bit RGBA PNG (debug and test artefacts).
void writePngRgba(const std::string& path, const Image& img);
// Portable float map (binary "PF", little-endian, bottom row first as the format says): the
// composited colour over `background`, unquantised, for comparisons finer than 8 bits allow.
void writePfm(const std::string& path, const Image& img, const glm::vec3& background);
Image readPfm(const std::string& path);  // alpha = 1
// Writes PNG or PFM by the file's extension (.png, .pfm); throws for other extensions, and for a
// PFM without a background (the format has no alpha).
void writeImage(const std::string& path, const Image& img, const Background& background);
// Reads an 8-bit PNG as an opaque image (alpha = 1 unless the file has alpha); throws on failure.
Image readPng(const std::string& path);

struct ImageError {
  double rmse = 0, maxAbs = 0, psnr = 0;  // over all four channels; PSNR for peak 1
  int nanPixels = 0;                      // pixels with a non-finite channel in either image
};
ImageError compareImages(const Image& a, const Image& b);
// |a - b| per pixel (max over channels) times `scale`, as a grey-scale opaque image.
Image differenceImage(const Image& a, const Image& b, float scale = 10.0f);
// Per-pixel L2 norm of the RGBA difference mapped through a heat colour map (the paper's figure).
Image l2Heatmap(const Image& a, const Image& b, float maxValue = 0.0f);

}  // namespace sm::scene
