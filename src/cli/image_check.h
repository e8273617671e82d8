// Image checks for regression tests in users' CI: `shellmarch compare RESULT BASELINE` and
// `shellmarch render --compare BASELINE`. Two PNG or PFM images of one size are compared channel by
// channel (R, G, B, A) in 8-bit levels, 0..255: a PNG's values as stored, a PFM's floats times 255.
// A pixel is beyond the tolerance when one of its channels differs by more than --tolerance (or is
// not finite); the check passes when at most --max-share of the pixels are.
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "scene/image.h"

namespace sm::app {

struct CheckTolerance {
  double levels = 0;    // --tolerance: largest absolute difference of a channel, in 8-bit levels
  double maxShare = 0;  // --max-share: fraction of the pixels (0..1) allowed beyond it
};

// An image read for a check: PNG (8-bit, alpha 255 unless the file has alpha) or PFM (alpha 1).
struct CheckImage {
  std::string path;
  scene::Image image;
  bool eightBit = false;  // PNG: values are whole levels
};

struct ChannelError {
  double maxAbs = 0;  // levels
  double rmse = 0;    // levels
  double psnr = 0;    // dB for peak 255; +infinity when the channel is identical
};

struct ImageCheck {
  int width = 0, height = 0;
  std::array<ChannelError, 4> channels;  // R, G, B, A
  // Over R, G, B, and A when either image has a pixel that is not opaque (`alphaInAll`).
  ChannelError all;
  bool alphaInAll = false;
  uint64_t pixels = 0;
  uint64_t beyond = 0;     // pixels beyond the tolerance, the non-finite ones included
  uint64_t nonFinite = 0;  // pixels with a channel that is not finite (PFM) in either image
  bool passed = true;
  double share() const { return pixels ? double(beyond) / double(pixels) : 0.0; }
};

// Reads a .png or .pfm (by its extension); throws UsageError naming the file and `role`
// ("RESULT", "--compare") when it cannot.
CheckImage readCheckImage(const std::string& path, const std::string& role);

// Throws UsageError naming both files when the sizes differ.
ImageCheck checkImages(const CheckImage& result, const CheckImage& baseline,
                       const CheckTolerance& tolerance);

// Where the differences are (as pixelmatch draws them): pixels beyond the tolerance red, pixels
// that differ within it yellow, equal pixels the result's grey level faded towards white.
scene::Image checkDifferenceImage(const CheckImage& result, const CheckImage& baseline,
                                  const CheckTolerance& tolerance);

// RESULT.png -> RESULT.diff.png, beside it.
std::string defaultDiffPath(const std::string& result);

struct CheckFiles {
  std::string result, baseline;
  std::string resultRole = "RESULT", baselineRole = "BASELINE";  // in messages: "--out" ...
  std::string diff;                                              // "" = defaultDiffPath(result)
  std::string json;                                              // "" = none
  CheckTolerance tolerance;
};

// Refuses (UsageError) a --diff or --json that is one of the images or each other, and a --diff
// that does not end in .png.
void checkOutputNames(const CheckFiles& files);

// Reads both images, compares them, writes the difference image (atomically) and the JSON, and
// prints the table to `out`. Throws UsageError for unreadable images or different sizes.
ImageCheck runImageCheck(const CheckFiles& files, std::ostream& out);

// The table `runImageCheck` prints, and its JSON (PSNR null where infinite).
std::string checkTable(const ImageCheck& check, const CheckFiles& files);
nlohmann::ordered_json checkJson(const ImageCheck& check, const CheckFiles& files);

// The one line of error for a check that failed (exit status 1).
std::string checkFailure(const ImageCheck& check, const CheckFiles& files);

// Adds --tolerance and --max-share (checked while parsing: finite, >= 0, the share <= 1).
std::pair<CLI::Option*, CLI::Option*> addToleranceOptions(CLI::App* cmd, CheckTolerance& tolerance);

}  // namespace sm::app
