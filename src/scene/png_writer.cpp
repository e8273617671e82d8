#include "scene/png_writer.h"

#include <png.h>

#include <csetjmp>
#include <cstdio>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>

#include "common/error.h"

namespace sm::scene {
namespace {

// What libpng's callbacks report back; plain data, because libpng leaves them by longjmp.
struct PngSink {
  std::vector<uint8_t>* out = nullptr;
  bool outOfMemory = false;
  char message[160] = {};
};

void onError(png_structp png, png_const_charp message) {
  auto* sink = static_cast<PngSink*>(png_get_error_ptr(png));
  std::snprintf(sink->message, sizeof sink->message, "%s", message);
  png_longjmp(png, 1);
}

void onWarning(png_structp, png_const_charp) {}  // nothing a user could act on

void onWrite(png_structp png, png_bytep data, size_t size) {
  auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
  if (sink->outOfMemory) return;
  try {
    sink->out->insert(sink->out->end(), data, data + size);
  } catch (...) {  // no exception may cross libpng's C frames
    sink->outOfMemory = true;
  }
}

void onFlush(png_structp) {}

// Returns false with sink.message set when libpng fails. No object with a destructor lives in
// this frame after setjmp: libpng's errors leave through longjmp.
bool encodeWithLibpng(PngSink& sink, const uint8_t* pixels, int width, int height, int channels,
                      int level) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, onError, onWarning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    return false;
  }
  png_set_write_fn(png, &sink, onWrite, onFlush);
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8,
               channels == 4 ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, level);
  png_write_info(png, info);
  const size_t stride = size_t(width) * size_t(channels);
  for (int y = 0; y < height; ++y) png_write_row(png, pixels + size_t(y) * stride);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

void checkSizes(std::span<const uint8_t> pixels, int width, int height, int channels) {
  if (width <= 0 || height <= 0 || (channels != 3 && channels != 4) ||
      pixels.size() != size_t(width) * size_t(height) * size_t(channels))
    throw Error("PNG encoding: ", pixels.size(), " bytes are not ", width, "x", height, "x",
                channels);
}

}  // namespace

std::vector<uint8_t> encodePng(std::span<const uint8_t> pixels, int width, int height, int channels,
                               int level) {
  checkSizes(pixels, width, height, channels);
  if (level < 0 || level > 9) throw Error("PNG encoding: level ", level, " is not in 0-9");
  std::vector<uint8_t> out;
  out.reserve(pixels.size() / 2 + 1024);  // rendered frames compress well below half
  PngSink sink;
  sink.out = &out;
  if (!encodeWithLibpng(sink, pixels.data(), width, height, channels, level))
    throw Error("PNG encoding failed: ", sink.message[0] ? sink.message : "libpng out of memory");
  if (sink.outOfMemory) throw Error("PNG encoding failed: out of memory");
  return out;
}

std::vector<uint8_t> encodePngStb(std::span<const uint8_t> pixels, int width, int height,
                                  int channels) {
  checkSizes(pixels, width, height, channels);
  std::vector<uint8_t> png;
  auto sink = [](void* ctx, void* data, int size) {
    auto* out = static_cast<std::vector<uint8_t>*>(ctx);
    auto* p = static_cast<uint8_t*>(data);
    out->insert(out->end(), p, p + size);
  };
  if (!stbi_write_png_to_func(sink, &png, width, height, channels, pixels.data(), width * channels))
    throw Error("PNG encoding (stb) failed");
  return png;
}

}  // namespace sm::scene
