// Text drawn into images (the colour legend's title and labels): a TrueType font rasterised by
// stb_truetype, anti-aliased, the text in UTF-8, so that a field named "ρ" or "T [°C]" reads as
// the file spells it. The font is DejaVu Sans (Debian's fonts-dejavu-core) unless
// $SHELLMARCH_FONT names another TrueType file, or "bitmap" for the built-in 5x7 font. A font
// that cannot be read falls back to the 5x7 bitmap font (ASCII; any other character shows as
// '?'), with one warning: text is never a reason for a render to fail.
//
// Inside a TrueType font: invalid UTF-8 (a stray byte, a truncated or overlong sequence, a
// surrogate) shows as U+FFFD, and so do control characters and characters the font has no glyph
// for ('?' if the font lacks U+FFFD too). Only trusted font files should be named: stb_truetype
// does not check them.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>

namespace sm::scene {

constexpr const char* kDefaultFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
constexpr char32_t kReplacementCharacter = 0xFFFD;

// UTF-8 to code points; each invalid byte, and each sequence cut short, becomes U+FFFD.
std::u32string decodeUtf8(std::string_view text);

class TextFont {
 public:
  TextFont();  // the 5x7 bitmap font
  // Reads a TrueType (.ttf) file; throws sm::FileError when it cannot be read or is not a font.
  static TextFont load(const std::string& path);
  // $SHELLMARCH_FONT ("bitmap": the 5x7 font), else kDefaultFontPath; a font that cannot be
  // loaded gives the bitmap font and one warning line naming it.
  static TextFont fromEnvironment();
  // fromEnvironment(), read once per process (legends drawn in every frame share it).
  static const TextFont& legend();

  bool trueType() const { return face_ != nullptr; }
  // Sizes at `scale`, the legend's pixels per dot of the 5x7 font (a TrueType line is 12 * scale
  // pixels from ascent to descent). height: the box every pixel drawn lies in; middle: from the
  // box's top to the middle of a digit, for text centred on a mark.
  int height(int scale) const;
  int middle(int scale) const;
  // Pixels from the leftmost pixel drawn to the rightmost, plus one; 0 for text with no ink.
  int width(std::string_view utf8, int scale) const;
  // Calls cover(x, y, coverage in (0, 1]) once for every pixel of `utf8` drawn in the box whose
  // top-left corner is (x, y), width(utf8) x height() pixels; no clipping to an image.
  void draw(std::string_view utf8, int x, int y, int scale,
            const std::function<void(int x, int y, float coverage)>& cover) const;

  struct Face;  // the font file and stb_truetype's view of it

 private:
  explicit TextFont(std::shared_ptr<const Face> face) : face_(std::move(face)) {}
  std::shared_ptr<const Face> face_;  // null: the bitmap font
};

}  // namespace sm::scene
