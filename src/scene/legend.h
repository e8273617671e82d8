// The colour legend (scalar bar) of `render --legend`, as ParaView and VisIt draw one beside a
// volume: the colour map as a vertical bar at the right of the image, the field's name above it
// and marks beside it (legendTicks), in the legend's font (scene/text_font.h: DejaVu Sans,
// anti-aliased, UTF-8; the 5x7 bitmap font where no font file can be read). Drawn opaque into the
// composited image, so it reads the same over any background; text is white over a dark
// background and black over a light one, and black over a transparent one (as on a page). The
// text grows with the image (scale: 1 below 360 rows, 2 below 900, then one per 300 rows).
#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/image.h"
#include "scene/transfer_function.h"

namespace sm::scene {

struct LegendLayout {
  int barX = 0, barY = 0, barWidth = 0, barHeight = 0;  // the colour bar, inside its frame
  int left = 0, top = 0, right = 0, bottom = 0;  // everything drawn: [left, right) x [top, bottom)
  int scale = 1;  // pixels per dot of the 5x7 font; the TrueType font's size follows it
};

// A mark beside the bar: where (0: the bottom, lo; 1: the top, hi) and its label ("" for a tick
// without one).
struct LegendTick {
  double at = 0.0;
  std::string text;
};

// Pixels from one label's row to the next at `scale`, the least labels are apart: a line of the
// legend's font and a gap.
int legendLineHeight(int scale);

// The marks of `tf`'s legend beside a bar `barHeight` pixels tall, at `scale` pixels per font
// dot (labels legendLineHeight(scale) apart at the least): the range's ends, and between them
// the middle on a linear scale; on a log scale, each power of ten inside the range, as ParaView
// marks decades (every n-th labelled so that labels never overlap, the rest ticks alone, and
// none where decades are too close to tell apart), or the geometric mean when no power of ten
// falls inside. Bottom to top.
std::vector<LegendTick> legendTicks(const TransferFunction& tf, int barHeight, int scale);

// Where drawLegend draws for a width x height image and these labels (clipped to the image).
LegendLayout legendLayout(int width, int height, const TransferFunction& tf,
                          const std::string& title);

// Draws the legend of `tf` (its colours from lo at the bottom to hi at the top) titled `title`
// (UTF-8), for an image written over `background` (std::nullopt: transparent). Text is blended
// by its coverage: over a background, onto the pixel composited over it (opaque, as the bar);
// over none, premultiplied "over" the pixel.
void drawLegend(Image& img, const TransferFunction& tf, const std::string& title,
                const Background& background);

}  // namespace sm::scene
