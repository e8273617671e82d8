// The legend's text: UTF-8 decoded (invalid bytes as U+FFFD), a TrueType font anti-aliased, every
// pixel inside the box the font says, and the 5x7 bitmap font where no font file can be read.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <utility>

#include "common/error.h"
#include "scene/legend.h"
#include "scene/text_font.h"
#include "support/test_support.h"

namespace sm::scene {
namespace {

using Coverage = std::map<std::pair<int, int>, float>;

Coverage coverage(const TextFont& font, const std::string& text, int scale) {
  Coverage c;
  font.draw(text, 0, 0, scale, [&](int x, int y, float v) {
    EXPECT_TRUE(c.emplace(std::pair{x, y}, v).second) << "pixel said twice: " << x << "," << y;
  });
  return c;
}

// DejaVu Sans, which the package installs (fonts-dejavu-core); the tests need the real font.
TextFont dejaVu() {
  if (!std::filesystem::exists(kDefaultFontPath)) ADD_FAILURE() << kDefaultFontPath << " missing";
  return TextFont::load(kDefaultFontPath);
}

// Sets $SHELLMARCH_FONT for one test, and puts back what it was.
class FontVariable {
 public:
  explicit FontVariable(const std::string& value) {
    if (const char* old = std::getenv("SHELLMARCH_FONT")) old_ = old;
    ::setenv("SHELLMARCH_FONT", value.c_str(), 1);
  }
  ~FontVariable() {
    if (old_.empty())
      ::unsetenv("SHELLMARCH_FONT");
    else
      ::setenv("SHELLMARCH_FONT", old_.c_str(), 1);
  }

 private:
  std::string old_;
};

TEST(Utf8, DecodesCodePointsAndReplacesEachInvalidSequence) {
  EXPECT_EQ(decodeUtf8("T [\xC2\xB0"
                       "C]"),
            std::u32string(U"T [\u00B0C]"));
  EXPECT_EQ(decodeUtf8("\xCF\x81"), std::u32string(U"\u03C1"));  // rho
  EXPECT_EQ(decodeUtf8("\xF0\x9F\x98\x80"
                       "a"),
            std::u32string(U"\U0001F600a"));
  const char32_t bad = kReplacementCharacter;
  EXPECT_EQ(decodeUtf8("a\xFF"
                       "b"),
            (std::u32string{U'a', bad, U'b'}));                 // not a lead byte
  EXPECT_EQ(decodeUtf8("a\xCF"), (std::u32string{U'a', bad}));  // cut short
  EXPECT_EQ(decodeUtf8("\xE2\x82"
                       "x"),
            (std::u32string{bad, U'x'}));                            // cut short
  EXPECT_EQ(decodeUtf8("\xC0\xAF"), (std::u32string{bad, bad}));     // overlong '/'
  EXPECT_EQ(decodeUtf8("\xE0\x80\xAF"), (std::u32string{bad}));      // overlong
  EXPECT_EQ(decodeUtf8("\xED\xA0\x80"), (std::u32string{bad}));      // a surrogate
  EXPECT_EQ(decodeUtf8("\xF4\x90\x80\x80"), (std::u32string{bad}));  // > U+10FFFF
  EXPECT_EQ(decodeUtf8("\x80\x80"), (std::u32string{bad, bad}));     // stray bytes
  EXPECT_EQ(decodeUtf8(""), std::u32string());
}

// "ρ" and "T [°C]" are drawn as their glyphs: not as '?' (what the 5x7 font showed), not as the
// replacement character, and anti-aliased (coverage between none and full).
TEST(TextFont, GreekAndDegreeSignDrawAsTheirGlyphs) {
  const TextFont font = dejaVu();
  ASSERT_TRUE(font.trueType());
  const Coverage rho = coverage(font, "\xCF\x81", 2);
  EXPECT_NE(rho, coverage(font, "?", 2));
  EXPECT_NE(rho, coverage(font, "\xEF\xBF\xBD", 2));
  EXPECT_NE(coverage(font,
                     "T [\xC2\xB0"
                     "C]",
                     2),
            coverage(font, "T [?C]", 2));
  int partial = 0, full = 0;
  for (const auto& [at, v] : rho) {
    EXPECT_GT(v, 0.0f);
    EXPECT_LE(v, 1.0f);
    partial += v < 0.99f;
    full += v >= 0.99f;
  }
  EXPECT_GT(partial, 4);  // edges blended
  EXPECT_GT(full, 4);     // the stroke's core solid
  // A character the font lacks draws as the replacement character.
  EXPECT_EQ(coverage(font, "\xF3\xA0\x80\x80", 2), coverage(font, "\xEF\xBF\xBD", 2));  // U+E0000
}

// Every pixel lies in the box width() x height() says; a TrueType box is tight left and right.
TEST(TextFont, EveryPixelLiesInItsBox) {
  for (const TextFont& font : {dejaVu(), TextFont()})
    for (int scale : {1, 2, 3, 5})
      for (const std::string text : {"\xCF\x81",
                                     "T [\xC2\xB0"
                                     "C]",
                                     "jÅgy|}_", "1e-07", "W"}) {
        const int w = font.width(text, scale), h = font.height(scale);
        ASSERT_GT(w, 0);
        int left = w, right = -1;
        font.draw(text, 10, 20, scale, [&](int x, int y, float) {
          EXPECT_TRUE(x >= 10 && x < 10 + w && y >= 20 && y < 20 + h)
              << text << " x" << scale << ": " << x << "," << y;
          left = std::min(left, x - 10);
          right = std::max(right, x - 10);
        });
        if (font.trueType()) {  // the 5x7 font's box is its cells, blank columns included
          EXPECT_EQ(left, 0) << text << " x" << scale;
          EXPECT_EQ(right, w - 1) << text << " x" << scale;
        }
        EXPECT_GT(font.middle(scale), 0);
        EXPECT_LT(font.middle(scale), h);
      }
  // The TrueType text grows with the scale.
  EXPECT_GT(dejaVu().width("pressure", 3), 2 * dejaVu().width("pressure", 1));
}

TEST(TextFont, InvalidUtf8DrawsReplacementCharactersAndNeverCrashes) {
  const TextFont font = dejaVu();
  EXPECT_EQ(coverage(font, "a\xFF", 1), coverage(font, "a\xEF\xBF\xBD", 1));
  for (const std::string& text :
       {std::string("\xFF\xFE\xFD"), std::string("\xC3"), std::string("\xED\xA0\x80"),
        std::string("ab\0cd", 5), std::string("\t\n\x7F"), std::string(300, '\x80')})
    for (const TextFont& f : {font, TextFont()}) {
      EXPECT_GT(f.width(text, 2), 0);
      int pixels = 0;
      f.draw(text, 0, 0, 2, [&](int, int, float) { ++pixels; });
      EXPECT_GT(pixels, 0);
    }
  // Through the legend as a title.
  TransferFunction tf = makeTransferFunction("viridis");
  Image img(200, 150);
  drawLegend(img, tf, "\xFF\xC3(\xED\xA0\x80", glm::vec3(0.0f));
}

// The 5x7 font knows ASCII only: any other character is one '?' (not one per UTF-8 byte).
TEST(TextFont, TheBitmapFontShowsOneQuestionMarkPerCharacter) {
  const TextFont bitmap;
  EXPECT_FALSE(bitmap.trueType());
  EXPECT_EQ(coverage(bitmap, "\xCF\x81", 1), coverage(bitmap, "?", 1));
  EXPECT_EQ(coverage(bitmap,
                     "T [\xC2\xB0"
                     "C]",
                     1),
            coverage(bitmap, "T [?C]", 1));
  for (const auto& [at, v] : coverage(bitmap, "p", 2)) EXPECT_EQ(v, 1.0f);
}

// A font that cannot be read is a warning, and the legend is drawn in the bitmap font.
TEST(TextFont, AMissingOrBrokenFontFallsBackToTheBitmapFont) {
  const std::string dir = test::outputDir("TextFont.Fallback");
  const std::string missing = dir + "/no-such-font.ttf", broken = dir + "/broken.ttf";
  std::filesystem::remove(missing);
  std::ofstream(broken) << "not a font at all, but long enough to be read";
  EXPECT_THROW(TextFont::load(missing), FileError);
  EXPECT_THROW(TextFont::load(broken), FileError);
  for (const std::string& path : {missing, broken}) {
    FontVariable font(path);
    testing::internal::CaptureStderr();
    const TextFont f = TextFont::fromEnvironment();
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_FALSE(f.trueType()) << path;
    EXPECT_NE(err.find("legend font"), std::string::npos) << err;
    EXPECT_NE(err.find(path), std::string::npos) << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;  // one line
  }
  {
    FontVariable font("bitmap");  // asked for: no warning
    testing::internal::CaptureStderr();
    EXPECT_FALSE(TextFont::fromEnvironment().trueType());
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  }
  {
    FontVariable font(kDefaultFontPath);
    EXPECT_TRUE(TextFont::fromEnvironment().trueType());
  }
}

}  // namespace
}  // namespace sm::scene
