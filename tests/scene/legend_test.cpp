// The colour legend of `render --legend`: it draws only inside its layout, its bar runs from the
// colour map's first entry at the bottom to its last at the top, its ink follows the background,
// its labels move the bar to make room for them, and its text (anti-aliased, UTF-8) shows a
// field's name as the file spells it.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <utility>

#include "scene/bitmap_font.h"
#include "scene/legend.h"
#include "scene/text_font.h"

namespace sm::scene {
namespace {

const glm::vec4 kUntouched(0.25f, 0.5f, 0.75f, 0.5f);

Image filled(int w, int h) {
  Image img(w, h);
  for (glm::vec4& p : img.pixels) p = kUntouched;
  return img;
}

TransferFunction viridis(double lo, double hi) {
  TransferFunction tf = makeTransferFunction("viridis");
  tf.lo = lo;
  tf.hi = hi;
  return tf;
}

bool inside(const LegendLayout& l, int x, int y) {
  return x >= l.left && x < l.right && y >= l.top && y < l.bottom;
}

TEST(Legend, DrawsOnlyInsideItsLayoutAndTheBarRunsLoToHi) {
  const TransferFunction tf = viridis(-2.0, 3.0);
  Image img = filled(320, 240);
  drawLegend(img, tf, "pressure", glm::vec3(0.0f));
  const LegendLayout l = legendLayout(img.width, img.height, tf, "pressure");
  ASSERT_GT(l.barWidth, 0);
  ASSERT_GT(l.barHeight, 1);
  EXPECT_GE(l.left, img.width / 2);  // at the right, clear of most of the view
  EXPECT_LE(l.right, img.width);
  int changed = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      if (img.at(x, y) == kUntouched) continue;
      ++changed;
      EXPECT_TRUE(inside(l, x, y)) << x << "," << y;
      EXPECT_EQ(img.at(x, y).a, 1.0f) << x << "," << y;  // opaque: reads the same on any background
    }
  EXPECT_GT(changed, l.barWidth * l.barHeight);  // the bar, its frame and the text
  const int cx = l.barX + l.barWidth / 2;
  const glm::vec4 top = img.at(cx, l.barY), bottom = img.at(cx, l.barY + l.barHeight - 1);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(top[c], tf.table.back()[c], 1e-6);
    EXPECT_NEAR(bottom[c], tf.table.front()[c], 1e-6);
  }
  // The middle row shows the middle of the map, as a lookup of the range's middle does.
  const glm::dvec4 mid = tf.lookup(0.5);
  const glm::vec4 m = img.at(cx, l.barY + (l.barHeight - 1) / 2);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[c], mid[c], 0.02);
}

// At every font scale, and with long labels and title, nothing lands outside the layout.
TEST(Legend, EveryScaleStaysInsideItsLayout) {
  for (auto [w, h] : {std::pair{320, 240}, {640, 480}, {1200, 1000}}) {
    const TransferFunction tf = viridis(-1.25e-7, 98765.4321);
    const std::string title = "turbulent kinetic energy";
    Image img = filled(w, h);
    drawLegend(img, tf, title, glm::vec3(1.0f));
    const LegendLayout l = legendLayout(w, h, tf, title);
    int changed = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        if (img.at(x, y) != kUntouched) {
          ++changed;
          EXPECT_TRUE(inside(l, x, y)) << w << "x" << h << ": " << x << "," << y;
        }
    EXPECT_GT(changed, l.barWidth * l.barHeight) << w << "x" << h;
  }
}

TEST(Legend, InkIsWhiteOnDarkAndBlackOnLight) {
  const TransferFunction tf = viridis(0.0, 1.0);
  Image dark = filled(256, 192), light = filled(256, 192);
  const glm::vec3 darkBg(0.1f, 0.1f, 0.12f), lightBg(1.0f);
  drawLegend(dark, tf, "t", darkBg);
  drawLegend(light, tf, "t", lightBg);
  int ink = 0, blended = 0;
  for (size_t i = 0; i < dark.pixels.size(); ++i) {
    if (dark.pixels[i] == glm::vec4(1.0f)) {
      ++ink;
      EXPECT_EQ(light.pixels[i], glm::vec4(0, 0, 0, 1));
    } else if (dark.pixels[i] != light.pixels[i]) {
      // Text's edges: the ink by its coverage over the pixel composited over the background,
      // opaque; the same coverage on either background.
      ++blended;
      const glm::vec3 overDark = glm::vec3(kUntouched) + (1.0f - kUntouched.a) * darkBg,
                      overLight = glm::vec3(kUntouched) + (1.0f - kUntouched.a) * lightBg;
      for (int c = 0; c < 3; ++c) {
        const float byDark = (dark.pixels[i][c] - overDark[c]) / (1.0f - overDark[c]),
                    byLight = 1.0f - light.pixels[i][c] / overLight[c];
        EXPECT_GT(byDark, 0.0f) << i;
        EXPECT_LT(byDark, 1.0f) << i;
        EXPECT_NEAR(byDark, byLight, 1e-5) << i;
      }
      EXPECT_EQ(dark.pixels[i].a, 1.0f);
      EXPECT_EQ(light.pixels[i].a, 1.0f);
    }
  }
  // More than the frame: the text is there too.
  const LegendLayout l = legendLayout(256, 192, tf, "t");
  const int frame =
      (l.barWidth + 2 * l.scale) * (l.barHeight + 2 * l.scale) - l.barWidth * l.barHeight;
  EXPECT_GT(ink, frame);
  if (TextFont::legend().trueType()) {
    EXPECT_GT(blended, 10);  // anti-aliased
  }
}

TEST(Legend, WiderLabelsMoveTheBarLeftAndLargeImagesScaleTheFont) {
  const LegendLayout narrow = legendLayout(512, 384, viridis(0.0, 1.0), "p");
  const LegendLayout wide = legendLayout(512, 384, viridis(-123456.0, 98765.4), "p");
  EXPECT_LT(wide.barX, narrow.barX);
  EXPECT_EQ(wide.right, narrow.right);
  EXPECT_EQ(legendLayout(256, 192, viridis(0, 1), "p").scale, 1);
  EXPECT_EQ(narrow.scale, 2);
  EXPECT_EQ(legendLayout(1024, 1024, viridis(0, 1), "p").scale, 3);
  EXPECT_EQ(legendLayout(4096, 3000, viridis(0, 1), "p").scale, 10);  // grows with the image
  EXPECT_GT(legendLineHeight(10), 4 * legendLineHeight(2));
}

TEST(Legend, ATinyImageIsClippedNotOverrun) {
  const TransferFunction tf = viridis(0.0, 1.0);
  Image img = filled(24, 16);  // smaller than the legend itself
  drawLegend(img, tf, "a long field name", glm::vec3(0.0f));
  EXPECT_EQ(img.pixels.size(), size_t(24 * 16));
  int changed = 0;
  for (const glm::vec4& p : img.pixels) changed += p != kUntouched;
  EXPECT_GT(changed, 0);
}

TransferFunction logViridis(double lo, double hi) {
  TransferFunction tf = viridis(lo, hi);
  tf.scale = ScalarScale::Log;
  return tf;
}

std::vector<std::string> texts(const std::vector<LegendTick>& ticks) {
  std::vector<std::string> out;
  for (const LegendTick& t : ticks) out.push_back(t.text);
  return out;
}

TEST(LegendTicks, ALinearScaleMarksTheEndsAndTheMiddle) {
  const auto t = legendTicks(viridis(-2.0, 3.0), 240, 1);
  EXPECT_EQ(texts(t), (std::vector<std::string>{"-2", "0.5", "3"}));
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t[0].at, 0.0);
  EXPECT_EQ(t[1].at, 0.5);
  EXPECT_EQ(t[2].at, 1.0);
}

// A constant field's legend would read "7 / 7 / 7": one mark in the middle instead.
TEST(LegendTicks, ARangeWhoseEndsReadAlikeIsMarkedOnce) {
  TransferFunction tf = makeTransferFunction("viridis");
  tf.lo = tf.hi = 7;  // a constant field
  std::vector<LegendTick> t = legendTicks(tf, 200, 1);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].text, "7");
  EXPECT_DOUBLE_EQ(t[0].at, 0.5);
  tf.hi = 7.0000001;  // ends that print alike
  EXPECT_EQ(legendTicks(tf, 200, 1).size(), 1u);
}

// Where each decade sits is where the colour map puts its value: the bar's coordinate of 10^e.
TEST(LegendTicks, ALogScaleMarksEachDecadeWhereTheMapPutsIt) {
  const TransferFunction tf = logViridis(0.5, 2000.0);
  const auto t = legendTicks(tf, 240, 1);
  EXPECT_EQ(texts(t), (std::vector<std::string>{"0.5", "1", "10", "100", "1000", "2000"}));
  for (size_t i = 1; i + 1 < t.size(); ++i)
    EXPECT_NEAR(t[i].at, tf.coordinate(std::stod(t[i].text)), 1e-12) << t[i].text;
  // Far from 1, decades read as powers, as the ends do.
  EXPECT_EQ(texts(legendTicks(logViridis(3e-7, 2e-5), 240, 1)),
            (std::vector<std::string>{"3e-07", "1e-06", "1e-05", "2e-05"}));
  // A decade at an end is that end's label, not a second one beside it.
  EXPECT_EQ(texts(legendTicks(logViridis(1.0, 1000.0), 240, 1)),
            (std::vector<std::string>{"1", "10", "100", "1000"}));
}

TEST(LegendTicks, WithoutADecadeInsideALogScaleMarksTheGeometricMean) {
  const auto t = legendTicks(logViridis(2.0, 8.0), 240, 1);
  EXPECT_EQ(texts(t), (std::vector<std::string>{"2", "4", "8"}));
  EXPECT_EQ(t[1].at, 0.5);
}

// Thirty decades on a short bar: labels every n-th decade, never closer than a line of text (nor
// to the ends'), and ticks alone dropped where decades crowd closer than the tick's own width.
TEST(LegendTicks, ManyDecadesLabelEveryNthAndNeverOverlap) {
  for (int height : {60, 120, 480}) {
    for (int scale : {1, 2}) {
      const auto t = legendTicks(logViridis(1e-15, 1e15), height, scale);
      const double line = double(legendLineHeight(scale)) / double(height - 1);
      double last = -1.0;
      int labelled = 0;
      for (const LegendTick& k : t) {
        if (k.text.empty()) continue;
        ++labelled;
        if (last >= 0.0) {
          EXPECT_GE(k.at - last, line - 1e-12) << height << " " << k.text;
        }
        last = k.at;
      }
      EXPECT_GE(labelled, 2) << height;
      // Decades are (height - 1) / 30 pixels apart: when labels skip some, those are ticks alone
      // if that is 3 dots or more, and left out if less.
      const double apart = double(height - 1) / 30.0;
      const bool skips = apart < double(legendLineHeight(scale));
      EXPECT_EQ(t.size() > size_t(labelled), skips && apart >= 3.0 * scale)
          << height << " x" << scale;
    }
  }
  // Decades about (L + 1) / 2 pixels apart, labels L = legendLineHeight(1) apart: every second
  // decade is labelled, the even ones that clear the ends' labels; the others are ticks alone.
  const int line = legendLineHeight(1), bar = 30 * (line + 1) / 2 + 1;
  std::vector<std::string> labels;
  for (const std::string& text : texts(legendTicks(logViridis(1e-15, 1e15), bar, 1)))
    if (!text.empty()) labels.push_back(text);
  EXPECT_EQ(labels, (std::vector<std::string>{"1e-15", "1e-12", "1e-10", "1e-08", "1e-06", "0.0001",
                                              "0.01", "1", "100", "1e+04", "1e+06", "1e+08",
                                              "1e+10", "1e+12", "1e+15"}));
}

// The drawn legend has a tick at each mark's row.
TEST(LegendTicks, EachMarkIsDrawnAtItsRow) {
  const TransferFunction tf = logViridis(0.5, 2000.0);
  Image img = filled(320, 240);
  drawLegend(img, tf, "density", glm::vec3(0.0f));
  const LegendLayout l = legendLayout(img.width, img.height, tf, "density");
  const int tickX = l.barX + l.barWidth + l.scale + 1;  // inside the tick, right of the frame
  for (const LegendTick& t : legendTicks(tf, l.barHeight, l.scale)) {
    const int row = l.barY + int(std::lround((1.0 - t.at) * double(l.barHeight - 1)));
    EXPECT_EQ(img.at(tickX, row), glm::vec4(1.0f)) << t.text;
  }
  // And nothing between marks, where no tick is.
  const int between = l.barY + int(std::lround(0.45 * double(l.barHeight - 1)));
  EXPECT_EQ(img.at(tickX, between), kUntouched);
}

TEST(BitmapFont, TextWidthAndDotsFollowTheGlyphs) {
  EXPECT_EQ(textWidth("", 2), 0);
  EXPECT_EQ(textWidth("A", 1), kGlyphWidth);
  EXPECT_EQ(textWidth("AB", 2), (2 * kGlyphAdvance - 1) * 2);
  int dots = 0, expected = 0;
  drawText("1.", 10, 20, 3, [&](int x, int y) {
    ++dots;
    EXPECT_GE(x, 10);
    EXPECT_LT(x, 10 + textWidth("1.", 3));
    EXPECT_GE(y, 20);
    EXPECT_LT(y, 20 + kGlyphHeight * 3);
  });
  for (char c : {'1', '.'})
    for (int r = 0; r < kGlyphHeight; ++r) expected += __builtin_popcount(glyph(c)[r]);
  EXPECT_EQ(dots, expected * 9);
}

// Every printable ASCII character has a glyph of its own, so that a field's name reads as the file
// spells it ("p" and "P" are different fields to a solver); anything else shows as '?'.
TEST(BitmapFont, EveryPrintableCharacterHasItsOwnGlyph) {
  auto rows = [](char c) {
    return std::string(reinterpret_cast<const char*>(glyph(c)), kGlyphHeight);
  };
  std::set<std::string> seen;
  for (char c = ' '; c <= '~'; ++c) {
    const std::string g = rows(c);
    EXPECT_TRUE(seen.insert(g).second) << "'" << c << "' looks like another character";
    const bool blank = g == std::string(kGlyphHeight, '\0');
    EXPECT_EQ(blank, c == ' ') << "'" << c << "'";
    for (char r : g) EXPECT_EQ(uint8_t(r) & ~0x1Fu, 0u) << "'" << c << "' is wider than the font";
  }
  for (char c = 'a'; c <= 'z'; ++c) EXPECT_NE(rows(c), rows(char(c - 'a' + 'A'))) << c;
  for (char c : {'\n', '\t', '\x7f', '\xc3', '\xa9'})
    EXPECT_EQ(rows(c), rows('?')) << int(uint8_t(c));
}

TEST(Legend, TheTitleKeepsItsCase) {
  const TransferFunction tf = viridis(0.0, 1.0);
  Image lower = filled(320, 240), upper = filled(320, 240);
  drawLegend(lower, tf, "p", glm::vec3(0.0f));
  drawLegend(upper, tf, "P", glm::vec3(0.0f));
  const LegendLayout l = legendLayout(320, 240, tf, "p");
  int differ = 0;
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x)
      if (lower.at(x, y) != upper.at(x, y)) {
        ++differ;
        EXPECT_LT(y, l.top + TextFont::legend().height(l.scale)) << "only the title differs";
      }
  EXPECT_GT(differ, 10);
}

// A field named in Greek or with a degree sign reads as it is spelt, not as '?'.
TEST(Legend, GreekAndDegreeSignTitlesDrawAsGlyphs) {
  if (!TextFont::legend().trueType()) GTEST_SKIP() << "no TrueType font: the 5x7 font's '?'";
  const TransferFunction tf = viridis(0.0, 1.0);
  for (auto [name, ascii] : {std::pair{"\xCF\x81", "?"},
                             {"T [\xC2\xB0"
                              "C]",
                              "T [?C]"}}) {
    Image utf8 = filled(320, 240), question = filled(320, 240);
    drawLegend(utf8, tf, name, glm::vec3(0.0f));
    drawLegend(question, tf, ascii, glm::vec3(0.0f));
    int differ = 0;
    for (size_t i = 0; i < utf8.pixels.size(); ++i) differ += utf8.pixels[i] != question.pixels[i];
    EXPECT_GT(differ, 10) << ascii;
  }
}

// Over a transparent background the text is black (as on a page) and blended "over" the frame:
// its edges keep part of what lies beneath, alpha included; the bar and frame are opaque.
TEST(Legend, OverATransparentBackgroundTextIsBlackAndBlendedOver) {
  const TransferFunction tf = viridis(0.0, 1.0);
  Image img(320, 240);  // all transparent
  drawLegend(img, tf, "density", std::nullopt);
  const LegendLayout l = legendLayout(320, 240, tf, "density");
  int black = 0, partial = 0;
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x) {
      const glm::vec4& p = img.at(x, y);
      if (p == glm::vec4(0.0f)) continue;
      EXPECT_TRUE(inside(l, x, y)) << x << "," << y;
      black += p == glm::vec4(0, 0, 0, 1);
      if (p.a < 1.0f) {
        ++partial;
        EXPECT_EQ(glm::vec3(p), glm::vec3(0.0f));  // black ink over nothing: black, part opaque
      }
    }
  EXPECT_GT(black, l.barHeight * 2);  // the frame's sides at least
  if (TextFont::legend().trueType()) {
    EXPECT_GT(partial, 10);
  }
}

}  // namespace
}  // namespace sm::scene
