// PNG files: what toRgba8 says is what the file holds (over a background, and transparent with
// the colour un-premultiplied), libpng's files are smaller than stb's for the same pixels, and
// sizes or formats that cannot hold the image are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <glm/common.hpp>

#include "common/error.h"
#include "common/file_util.h"
#include "scene/image.h"
#include "scene/png_writer.h"
#include "support/test_support.h"

namespace sm::scene {
namespace {

// A frame as the renderer leaves it: premultiplied colour, smooth, partly transparent, with
// some noise so that the encoders have something to do.
Image frame(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> noise(-0.01f, 0.01f);
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float dx = (x - w / 2.0f) / w, dy = (y - h / 2.0f) / h;
      const float a =
          std::clamp(1.2f - 3.0f * std::sqrt(dx * dx + dy * dy) + noise(rng), 0.0f, 1.0f);
      const glm::vec3 c(0.5f + dx, 0.5f + dy + noise(rng), 0.8f - dx * dy);
      img.at(x, y) = glm::vec4(glm::clamp(c, 0.0f, 1.0f) * a, a);
    }
  return img;
}

std::vector<uint8_t> rgba8Of(const Image& img) {
  std::vector<uint8_t> out(img.pixels.size() * 4);
  for (size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 4; ++c) out[4 * i + c] = uint8_t(std::lround(img.pixels[i][c] * 255.0f));
  return out;
}

TEST(Png, TheFileHoldsWhatToRgba8Says) {
  const std::string dir = test::outputDir("Png.Bytes");
  const Image img = frame(67, 41, 1);  // odd sizes: rows not a multiple of anything
  for (const Background& bg : {Background(glm::vec3(0.1f, 0.2f, 0.3f)), Background()}) {
    const std::string path = dir + (bg ? "/opaque.png" : "/transparent.png");
    writePng(path, img, bg);
    const std::vector<uint8_t> want = toRgba8(img, bg), got = rgba8Of(readPng(path));
    EXPECT_EQ(got, want) << path;
    // Over a background the file is RGB (opaque); without one RGBA (colour type byte 25 of the
    // header: 2 = RGB, 6 = RGBA).
    EXPECT_EQ(readFile(path)[25], bg ? 2 : 6) << path;
  }
}

// Transparent: the colour divided by alpha, the alpha kept; a viewer compositing the file over
// a background gets what the opaque file holds, to the 8-bit rounding.
TEST(Png, TransparentKeepsTheColourUnpremultipliedAndTheAlpha) {
  Image img(3, 1);
  img.at(0, 0) = glm::vec4(0.25f, 0.0f, 0.5f, 0.5f);  // (0.5, 0, 1) at half opacity
  img.at(1, 0) = glm::vec4(0.0f);                     // nothing: black, transparent
  img.at(2, 0) = glm::vec4(0.2f, 0.4f, 0.6f, 1.0f);   // opaque: as it is
  const std::vector<uint8_t> t = toRgba8(img, std::nullopt);
  EXPECT_EQ(t, (std::vector<uint8_t>{128, 0, 255, 128, 0, 0, 0, 0, 51, 102, 153, 255}));
  const glm::vec3 bg(0.9f, 0.6f, 0.3f);
  const Image f = frame(50, 50, 2);
  const std::vector<uint8_t> over = toRgba8(f, bg), clear = toRgba8(f, std::nullopt);
  for (size_t i = 0; i < f.pixels.size(); ++i) {
    EXPECT_EQ(over[4 * i + 3], 255);
    const float a = clear[4 * i + 3] / 255.0f;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(clear[4 * i + c] / 255.0f * a + (1.0f - a) * bg[c], over[4 * i + c] / 255.0f,
                  1.5f / 255.0f)
          << i;
  }
}

// libpng at kPngLevel against stb_image_write on the same pixels: the same image back, fewer bytes.
TEST(Png, LibpngFilesAreSmallerThanStbs) {
  const Image img = frame(256, 256, 3);
  for (const Background& bg : {Background(glm::vec3(0.0f)), Background()}) {
    std::vector<uint8_t> raw = toRgba8(img, bg);
    const std::vector<uint8_t> ours = encodePng(raw, 256, 256, 4),
                               stb = encodePngStb(raw, 256, 256, 4);
    EXPECT_LT(ours.size(), stb.size());
    const std::string dir = test::outputDir("Png.Sizes");
    writeBytesAtomically(dir + "/libpng.png", ours);
    writeBytesAtomically(dir + "/stb.png", stb);
    EXPECT_EQ(rgba8Of(readPng(dir + "/libpng.png")), raw);
    EXPECT_EQ(rgba8Of(readPng(dir + "/stb.png")), raw);
  }
}

TEST(Png, SizesAndFormatsThatCannotHoldTheImageAreRefused) {
  std::vector<uint8_t> raw(10 * 10 * 3);
  EXPECT_THROW(encodePng(raw, 10, 10, 4), Error);
  EXPECT_THROW(encodePng(raw, 0, 10, 3), Error);
  EXPECT_THROW(encodePng(raw, 10, 10, 2), Error);
  EXPECT_THROW(encodePng(raw, 10, 10, 3, 10), Error);
  EXPECT_NO_THROW(encodePng(raw, 10, 10, 3, 0));
  const std::string dir = test::outputDir("Png.Refused");
  EXPECT_THROW(writeImage(dir + "/a.pfm", frame(4, 4, 4), std::nullopt), Error);
  EXPECT_THROW(writePng(dir + "/no-such-folder/a.png", frame(4, 4, 4), glm::vec3(0.0f)), Error);
}

}  // namespace
}  // namespace sm::scene
