#include "scene/image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <glm/common.hpp>
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

#include "common/error.h"
#include "common/file_util.h"
#include "common/setting_error.h"
#include "scene/png_writer.h"

namespace sm::scene {
namespace {

uint8_t toByte(float v) {
  if (!std::isfinite(v)) v = 0.0f;
  return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

}  // namespace

std::vector<uint8_t> toRgba8(const Image& img, const Background& background) {
  std::vector<uint8_t> raw(img.pixels.size() * 4);
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    const glm::vec4& p = img.pixels[i];
    glm::vec3 c;
    float a = 1.0f;
    if (background) {
      c = glm::vec3(p) + (1.0f - p.a) * *background;
    } else {
      a = std::isfinite(p.a) ? std::clamp(p.a, 0.0f, 1.0f) : 0.0f;
      c = a > 0.0f ? glm::vec3(p) / a : glm::vec3(0.0f);
    }
    raw[4 * i] = toByte(c.r);
    raw[4 * i + 1] = toByte(c.g);
    raw[4 * i + 2] = toByte(c.b);
    raw[4 * i + 3] = toByte(a);
  }
  return raw;
}

void writePng(const std::string& path, const Image& img, const Background& background) {
  std::vector<uint8_t> raw = toRgba8(img, background);
  int channels = 4;
  if (background) {  // opaque: RGB, a quarter smaller before compression
    for (size_t i = 0; i < img.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c) raw[3 * i + c] = raw[4 * i + c];
    raw.resize(img.pixels.size() * 3);
    channels = 3;
  }
  std::vector<uint8_t> png;
  try {
    png = encodePng(raw, img.width, img.height, channels);
  } catch (const Error& e) {
    throw Error(path, ": ", e.what());
  }
  writeBytesAtomically(path, png);
}

void writePngRgba(const std::string& path, const Image& img) {
  std::vector<uint8_t> raw(size_t(img.width) * img.height * 4);
  for (size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 4; ++c) raw[4 * i + c] = toByte(img.pixels[i][c]);
  writeBytesAtomically(path, encodePng(raw, img.width, img.height, 4));
}

void writePfm(const std::string& path, const Image& img, const glm::vec3& bg) {
  std::string header =
      "PF\n" + std::to_string(img.width) + " " + std::to_string(img.height) + "\n-1.0\n";
  std::vector<uint8_t> bytes(header.begin(), header.end());
  bytes.reserve(bytes.size() + size_t(img.width) * img.height * 12);
  for (int y = img.height - 1; y >= 0; --y) {
    for (int x = 0; x < img.width; ++x) {
      const glm::vec4& p = img.at(x, y);
      glm::vec3 c = glm::vec3(p) + (1.0f - p.a) * bg;
      const uint8_t* raw = reinterpret_cast<const uint8_t*>(&c);
      bytes.insert(bytes.end(), raw, raw + 12);
    }
  }
  writeBytesAtomically(path, bytes);
}

Image readPfm(const std::string& path) {
  auto bytes = readFile(path);
  std::string head(bytes.begin(), bytes.begin() + std::min<size_t>(bytes.size(), 64));
  int w = 0, h = 0, used = 0;
  float scale = 0;
  if (std::sscanf(head.c_str(), "PF %d %d %f%n", &w, &h, &scale, &used) != 3 || w <= 0 || h <= 0 ||
      scale >= 0)
    throw FileError(path, "not a little-endian colour PFM");
  size_t at = size_t(used) + 1;  // one whitespace byte ends the header
  if (bytes.size() < at + size_t(w) * h * 12) throw FileError(path, "truncated PFM");
  Image img(w, h);
  for (int y = h - 1; y >= 0; --y)
    for (int x = 0; x < w; ++x, at += 12) {
      glm::vec3 c;
      std::memcpy(&c, bytes.data() + at, 12);
      img.at(x, y) = glm::vec4(c, 1.0f);
    }
  return img;
}

void writeImage(const std::string& path, const Image& img, const Background& background) {
  std::string ext = fileExtension(path);
  if (ext == ".png") return writePng(path, img, background);
  if (ext == ".pfm" && !background)
    throw SettingError("out", "'", path,
                       "': a PFM has no alpha; a transparent background needs .png");
  if (ext == ".pfm") return writePfm(path, img, *background);
  throw SettingError("out", "'", path, "' must end in .png or .pfm");
}

Image readPng(const std::string& path) {
  auto bytes = readFile(path);
  int w = 0, h = 0, comp = 0;
  stbi_uc* data = stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &h, &comp, 4);
  if (!data) throw FileError(path, "not a readable PNG: ", stbi_failure_reason());
  Image img(w, h);
  for (size_t i = 0; i < size_t(w) * h; ++i)
    img.pixels[i] =
        glm::vec4(data[4 * i], data[4 * i + 1], data[4 * i + 2], data[4 * i + 3]) / 255.0f;
  stbi_image_free(data);
  return img;
}

ImageError compareImages(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height)
    throw Error("comparing images of different sizes: ", a.width, "x", a.height, " and ", b.width,
                "x", b.height);
  ImageError e;
  double sum = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    bool bad = false;
    for (int c = 0; c < 4; ++c) {
      double x = a.pixels[i][c], y = b.pixels[i][c];
      if (!std::isfinite(x) || !std::isfinite(y)) {
        bad = true;
        continue;
      }
      double d = std::abs(x - y);
      sum += d * d;
      e.maxAbs = std::max(e.maxAbs, d);
    }
    e.nanPixels += bad;
  }
  e.rmse = a.pixels.empty() ? 0.0 : std::sqrt(sum / (4.0 * a.pixels.size()));
  e.psnr = e.rmse > 0 ? 20.0 * std::log10(1.0 / e.rmse) : 99.0;
  return e;
}

Image differenceImage(const Image& a, const Image& b, float scale) {
  Image d(a.width, a.height);
  for (size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i) {
    glm::vec4 diff = glm::abs(a.pixels[i] - b.pixels[i]);
    float m = std::min(1.0f, std::max({diff.r, diff.g, diff.b, diff.a}) * scale);
    d.pixels[i] = glm::vec4(m, m, m, 1.0f);
  }
  return d;
}

Image l2Heatmap(const Image& a, const Image& b, float maxValue) {
  Image h(a.width, a.height);
  std::vector<float> l2(a.pixels.size());
  float mx = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    glm::vec4 d = a.pixels[i] - b.pixels[i];
    l2[i] = std::sqrt(d.r * d.r + d.g * d.g + d.b * d.b + d.a * d.a);
    mx = std::max(mx, l2[i]);
  }
  if (maxValue > 0) mx = maxValue;
  for (size_t i = 0; i < l2.size(); ++i) {
    float t = mx > 0 ? std::clamp(l2[i] / mx, 0.0f, 1.0f) : 0.0f;
    // black -> red -> yellow -> white
    glm::vec3 c(std::min(1.0f, 3 * t), std::clamp(3 * t - 1, 0.0f, 1.0f),
                std::clamp(3 * t - 2, 0.0f, 1.0f));
    h.pixels[i] = glm::vec4(c, 1.0f);
  }
  return h;
}

}  // namespace sm::scene
