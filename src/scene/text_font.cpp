#include "scene/text_font.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

#define STB_TRUETYPE_IMPLEMENTATION
#define STBTT_STATIC
#include <stb/stb_truetype.h>

#include "common/error.h"
#include "common/file_util.h"
#include "common/log.h"
#include "scene/bitmap_font.h"

namespace sm::scene {

struct TextFont::Face {
  std::vector<uint8_t> data;  // stb_truetype reads the file in place: kept as long as the face
  stbtt_fontinfo info{};
  int ascent = 0, descent = 0;  // font units; descent below the baseline is negative
  int digitTop = 0;             // the top of '0' above the baseline, font units
};

namespace {

constexpr int kPixelsPerScale = 12;  // a TrueType line's ascent to descent at scale 1

// The 5x7 font's characters: ASCII as it is, anything else (one '?' per character, not per byte).
std::string asciiOf(std::string_view utf8) {
  std::string out;
  for (char32_t c : decodeUtf8(utf8)) out += c >= 0x20 && c < 0x7F ? char(c) : '?';
  return out;
}

int glyphOf(const stbtt_fontinfo& info, char32_t c) {
  if (c < 0x20 || (c >= 0x7F && c < 0xA0)) c = kReplacementCharacter;  // controls: shown, not lost
  int g = stbtt_FindGlyphIndex(&info, int(c));
  if (g == 0) g = stbtt_FindGlyphIndex(&info, int(kReplacementCharacter));
  if (g == 0) g = stbtt_FindGlyphIndex(&info, '?');
  return g;
}

// A glyph where a line puts it: its index, its pixel box relative to the pen's whole pixel and
// the baseline, and the pen's fraction of a pixel (rasterised at that shift).
struct Placed {
  int glyph, penX;
  float shift;
  int x0, y0, x1, y1;
};

struct Line {
  std::vector<Placed> glyphs;
  int minX = 0, maxX = 0;  // ink, relative to the pen's start; equal when there is none
};

Line place(const stbtt_fontinfo& info, std::string_view utf8, float scale) {
  Line line;
  bool ink = false;
  float pen = 0.0f;
  int previous = 0;
  for (char32_t c : decodeUtf8(utf8)) {
    const int g = glyphOf(info, c);
    if (previous) pen += scale * float(stbtt_GetGlyphKernAdvance(&info, previous, g));
    Placed p{g, int(std::floor(pen)), 0.0f, 0, 0, 0, 0};
    p.shift = pen - float(p.penX);
    stbtt_GetGlyphBitmapBoxSubpixel(&info, g, scale, scale, p.shift, 0.0f, &p.x0, &p.y0, &p.x1,
                                    &p.y1);
    if (p.x1 > p.x0 && p.y1 > p.y0) {
      line.minX = ink ? std::min(line.minX, p.penX + p.x0) : p.penX + p.x0;
      line.maxX = ink ? std::max(line.maxX, p.penX + p.x1) : p.penX + p.x1;
      ink = true;
      line.glyphs.push_back(p);
    }
    int advance = 0, bearing = 0;
    stbtt_GetGlyphHMetrics(&info, g, &advance, &bearing);
    pen += scale * float(advance);
    previous = g;
  }
  return line;
}

float pixelScale(const TextFont::Face& f, int scale) {
  return stbtt_ScaleForPixelHeight(&f.info, float(kPixelsPerScale * std::max(scale, 1)));
}

int ascentPixels(const TextFont::Face& f, int scale) {
  return int(std::ceil(float(f.ascent) * pixelScale(f, scale)));
}

// A line's coverage, w x h (the font's line height) from the glyphs' boxes, and the columns that
// hold ink: first..last (last < first when none). Glyph boxes may keep blank columns at their
// edges; the ink's extent is what width() says.
struct Raster {
  int w = 0, h = 0, first = 0, last = -1;
  std::vector<uint8_t> coverage;
};

Raster rasterise(const TextFont::Face& f, std::string_view utf8, int scale) {
  const float s = pixelScale(f, scale);
  const Line line = place(f.info, utf8, s);
  const int baseline = ascentPixels(f, scale);
  Raster r;
  r.w = line.maxX - line.minX;
  r.h = baseline + int(std::ceil(float(-f.descent) * s));
  if (r.w <= 0) return r;
  // Glyphs may overlap (kerning, accents): each pixel keeps the largest coverage.
  r.coverage.assign(size_t(r.w) * size_t(r.h), 0);
  std::vector<uint8_t> glyph;
  for (const Placed& p : line.glyphs) {
    const int gw = p.x1 - p.x0, gh = p.y1 - p.y0;
    glyph.assign(size_t(gw) * size_t(gh), 0);
    stbtt_MakeGlyphBitmapSubpixel(&f.info, glyph.data(), gw, gh, gw, s, s, p.shift, 0.0f, p.glyph);
    for (int gy = 0; gy < gh; ++gy)
      for (int gx = 0; gx < gw; ++gx) {
        const int cx = p.penX + p.x0 + gx - line.minX, cy = baseline + p.y0 + gy;
        if (cy < 0 || cy >= r.h) continue;  // beyond the font's ascent or descent
        uint8_t& c = r.coverage[size_t(cy) * size_t(r.w) + size_t(cx)];
        c = std::max(c, glyph[size_t(gy) * size_t(gw) + size_t(gx)]);
      }
  }
  r.first = r.w;
  for (int cy = 0; cy < r.h; ++cy)
    for (int cx = 0; cx < r.w; ++cx)
      if (r.coverage[size_t(cy) * size_t(r.w) + size_t(cx)]) {
        r.first = std::min(r.first, cx);
        r.last = std::max(r.last, cx);
      }
  return r;
}

}  // namespace

std::u32string decodeUtf8(std::string_view text) {
  std::u32string out;
  size_t i = 0;
  while (i < text.size()) {
    const uint8_t lead = uint8_t(text[i]);
    if (lead < 0x80) {
      out += char32_t(lead);
      ++i;
      continue;
    }
    // Lead bytes C0, C1 and F5-FF start only overlong or out-of-range sequences.
    const size_t n = lead >= 0xC2 && lead <= 0xDF   ? 1
                     : lead >= 0xE0 && lead <= 0xEF ? 2
                     : lead >= 0xF0 && lead <= 0xF4 ? 3
                                                    : 0;
    char32_t c = lead & (0x3F >> n);
    size_t j = 1;
    while (n && j <= n && i + j < text.size() && (uint8_t(text[i + j]) & 0xC0) == 0x80)
      c = (c << 6) | (uint8_t(text[i + j++]) & 0x3F);
    const char32_t least = n == 1 ? 0x80 : n == 2 ? 0x800 : 0x10000;
    const bool valid =
        n && j == n + 1 && c >= least && c <= 0x10FFFF && !(c >= 0xD800 && c <= 0xDFFF);
    out += valid ? c : kReplacementCharacter;
    i += std::max<size_t>(j, 1);
  }
  return out;
}

TextFont::TextFont() = default;

TextFont TextFont::load(const std::string& path) {
  auto face = std::make_shared<Face>();
  face->data = readFile(path);
  const int offset =
      face->data.size() >= 12 ? stbtt_GetFontOffsetForIndex(face->data.data(), 0) : -1;
  if (offset < 0 || !stbtt_InitFont(&face->info, face->data.data(), offset))
    throw FileError(path, "not a TrueType font");
  int gap = 0;
  stbtt_GetFontVMetrics(&face->info, &face->ascent, &face->descent, &gap);
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  if (!stbtt_GetCodepointBox(&face->info, '0', &x0, &y0, &x1, &y1)) y1 = face->ascent * 3 / 4;
  face->digitTop = y1;
  if (face->ascent <= face->descent) throw FileError(path, "a TrueType font without a height");
  return TextFont(std::move(face));
}

TextFont TextFont::fromEnvironment() {
  const char* env = std::getenv("SHELLMARCH_FONT");
  const std::string path = env && *env ? env : kDefaultFontPath;
  if (path == "bitmap") return TextFont();
  try {
    return load(path);
  } catch (const Error& e) {
    log::warning("legend font: ", e.what(),
                 "; drawing text in the built-in 5x7 font (ASCII only; SHELLMARCH_FONT names "
                 "another .ttf)");
    return TextFont();
  }
}

const TextFont& TextFont::legend() {
  static const TextFont font = fromEnvironment();
  return font;
}

int TextFont::height(int scale) const {
  if (!face_) return kGlyphHeight * scale;
  const float s = pixelScale(*face_, scale);
  return int(std::ceil(float(face_->ascent) * s)) + int(std::ceil(float(-face_->descent) * s));
}

int TextFont::middle(int scale) const {
  if (!face_) return kGlyphHeight * scale / 2;
  const float s = pixelScale(*face_, scale);
  return ascentPixels(*face_, scale) - int(std::lround(0.5f * float(face_->digitTop) * s));
}

int TextFont::width(std::string_view utf8, int scale) const {
  if (!face_) return textWidth(asciiOf(utf8), scale);
  const Raster r = rasterise(*face_, utf8, scale);
  return r.last >= r.first ? r.last - r.first + 1 : 0;
}

void TextFont::draw(std::string_view utf8, int x, int y, int scale,
                    const std::function<void(int x, int y, float coverage)>& cover) const {
  if (!face_) {
    drawText(asciiOf(utf8), x, y, scale, [&](int px, int py) { cover(px, py, 1.0f); });
    return;
  }
  const Raster r = rasterise(*face_, utf8, scale);
  for (int cy = 0; cy < r.h; ++cy)
    for (int cx = r.first; cx <= r.last; ++cx)
      if (const uint8_t c = r.coverage[size_t(cy) * size_t(r.w) + size_t(cx)])
        cover(x + cx - r.first, y + cy, float(c) / 255.0f);
}

}  // namespace sm::scene
