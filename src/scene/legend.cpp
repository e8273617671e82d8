#include "scene/legend.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "scene/text_font.h"

namespace sm::scene {
namespace {

std::string label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

// Powers of ten strictly inside a log scale's range, bottom to top, given rows `spacing` pixels
// apart at the least for labels and `tickSpacing` for ticks alone. Empty when none.
std::vector<LegendTick> decades(const TransferFunction& tf, double barPixels, double spacing,
                                double tickSpacing) {
  const double span = std::log10(tf.hi) - std::log10(tf.lo);
  if (!(tf.lo > 0.0) || !(span > 0.0) || !std::isfinite(span)) return {};
  // A decade within a hair of an end is that end, labelled already.
  const double eps = 1e-9 * span;
  const int first = int(std::ceil(std::log10(tf.lo) + eps)),
            last = int(std::floor(std::log10(tf.hi) - eps));
  if (first > last) return {};
  const double perDecade = barPixels / span;
  // Labels on every n-th decade (multiples of n, so that they read as a sequence).
  const int every = std::max(1, int(std::ceil(spacing / perDecade)));
  const bool ticks = perDecade >= tickSpacing;
  std::vector<LegendTick> out;
  for (int e = first; e <= last; ++e) {
    const double at = (double(e) - std::log10(tf.lo)) / span;
    // Clear of the ends' labels too.
    const bool room = at * barPixels >= spacing && (1.0 - at) * barPixels >= spacing;
    const bool labelled = room && e % every == 0;
    if (labelled || ticks) out.push_back({at, labelled ? label(std::pow(10.0, e)) : ""});
  }
  return out;
}

std::vector<std::string> labelTexts(const TransferFunction& tf, int barHeight, int scale) {
  std::vector<std::string> texts;
  for (const LegendTick& t : legendTicks(tf, barHeight, scale))
    if (!t.text.empty()) texts.push_back(t.text);
  return texts;
}

// The title as drawn: a log scale says so (its marks are decades, or the geometric mean).
std::string shownTitle(const TransferFunction& tf, const std::string& title) {
  return tf.scale == ScalarScale::Log ? title + " (log)" : title;
}

// The table's colour at x in [0, 1], interpolated as lookups are (whatever the range).
glm::vec3 tableColor(const TransferFunction& tf, double x) {
  if (tf.table.empty()) return glm::vec3(0.0f);
  const double at = std::clamp(x, 0.0, 1.0) * double(tf.table.size() - 1);
  const size_t i = std::min(size_t(at), tf.table.size() - 1),
               j = std::min(i + 1, tf.table.size() - 1);
  const double f = at - double(i);
  return glm::vec3(glm::dvec3(tf.table[i]) * (1.0 - f) + glm::dvec3(tf.table[j]) * f);
}

}  // namespace

int legendLineHeight(int scale) {
  return TextFont::legend().height(scale) + 2 * scale;
}

std::vector<LegendTick> legendTicks(const TransferFunction& tf, int barHeight, int scale) {
  const double pixels = double(std::max(barHeight - 1, 1));
  // A constant field (or a range narrower than the labels' digits) would read "7 / 7 / 7": one
  // mark in the middle says it.
  if (label(tf.lo) == label(tf.hi)) return {{0.5, label(tf.lo)}};
  std::vector<LegendTick> out = {{0.0, label(tf.lo)}};
  std::vector<LegendTick> inside;
  if (tf.scale == ScalarScale::Log)
    inside = decades(tf, pixels, double(legendLineHeight(scale)), double(3 * scale));
  if (inside.empty()) inside.push_back({0.5, label(tf.valueAt(0.5))});
  out.insert(out.end(), inside.begin(), inside.end());
  out.push_back({1.0, label(tf.hi)});
  return out;
}

LegendLayout legendLayout(int width, int height, const TransferFunction& tf,
                          const std::string& title) {
  const TextFont& font = TextFont::legend();
  LegendLayout l;
  l.scale = height >= 900 ? std::max(3, height / 300) : height >= 360 ? 2 : 1;
  const int s = l.scale, margin = 8 * s, gap = 3 * s, text = font.height(s);
  l.barWidth = 8 * s;
  l.barHeight = std::max(2, height / 2);
  int labelWidth = 0;
  for (const std::string& t : labelTexts(tf, l.barHeight, s))
    labelWidth = std::max(labelWidth, font.width(t, s));
  // The frame is one dot wide around the bar; ticks reach `gap` to the right of it.
  l.barX = width - margin - labelWidth - 2 * gap - l.barWidth - s;
  l.barY = (height - l.barHeight) / 2 + (text + 2 * s) / 2;
  const int titleY = l.barY - s - 3 * s - text;
  const int titleX = std::min(l.barX - s, width - margin - font.width(shownTitle(tf, title), s));
  l.left = std::min(l.barX - s, titleX);
  l.top = titleY;
  l.right = width - margin;
  // The frame's bottom, or the lowest label's, centred on the bar's last row.
  l.bottom = std::max(l.barY + l.barHeight + s, l.barY + l.barHeight - 1 - font.middle(s) + text);
  return l;
}

void drawLegend(Image& img, const TransferFunction& tf, const std::string& title,
                const Background& background) {
  const TextFont& font = TextFont::legend();
  const LegendLayout l = legendLayout(img.width, img.height, tf, title);
  const int s = l.scale, gap = 3 * s;
  const glm::vec3 under = background.value_or(glm::vec3(1.0f));  // transparent: as on a page
  const float luminance = 0.2126f * under.r + 0.7152f * under.g + 0.0722f * under.b;
  const glm::vec4 ink = luminance > 0.5f ? glm::vec4(0, 0, 0, 1) : glm::vec4(1, 1, 1, 1);
  auto set = [&](int x, int y, const glm::vec4& c) {
    if (x >= 0 && y >= 0 && x < img.width && y < img.height) img.at(x, y) = c;
  };
  // Anti-aliased text: ink over what lies beneath, by coverage. Over a background the pixel is
  // composited first, so that the legend stays opaque whatever the frame's alpha.
  auto blend = [&](int x, int y, float coverage) {
    if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
    glm::vec4& p = img.at(x, y);
    if (coverage >= 1.0f) {
      p = ink;
      return;
    }
    if (background) p = glm::vec4(glm::vec3(p) + (1.0f - p.a) * *background, 1.0f);
    p = ink * coverage + p * (1.0f - coverage);
  };
  for (int y = 0; y < l.barHeight; ++y) {
    const double x01 = l.barHeight > 1 ? 1.0 - double(y) / double(l.barHeight - 1) : 0.5;
    const glm::vec4 c(tableColor(tf, x01), 1.0f);
    for (int x = 0; x < l.barWidth; ++x) set(l.barX + x, l.barY + y, c);
  }
  // Frame: s pixels around the bar.
  for (int y = l.barY - s; y < l.barY + l.barHeight + s; ++y)
    for (int x = l.barX - s; x < l.barX + l.barWidth + s; ++x) {
      const bool inside =
          x >= l.barX && x < l.barX + l.barWidth && y >= l.barY && y < l.barY + l.barHeight;
      if (!inside) set(x, y, ink);
    }
  const int right = l.barX + l.barWidth + s;
  for (const LegendTick& t : legendTicks(tf, l.barHeight, s)) {
    const int ty = l.barY + int(std::lround((1.0 - t.at) * double(l.barHeight - 1)));
    for (int x = right; x < right + gap; ++x)
      for (int d = 0; d < s; ++d) set(x, ty + d - s / 2, ink);
    if (!t.text.empty()) font.draw(t.text, right + 2 * gap, ty - font.middle(s), s, blend);
  }
  const std::string shown = shownTitle(tf, title);
  font.draw(shown, std::min(l.barX - s, l.right - font.width(shown, s)),
            l.barY - s - 3 * s - font.height(s), s, blend);
}

}  // namespace sm::scene
