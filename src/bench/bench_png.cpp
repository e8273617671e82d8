// `shellmarch bench png`: the PNG encoders on one frame's pixels, stb_image_write (the encoder
// before libpng) against libpng at several zlib levels: bytes, and the median time to encode.
// The frame is a file `render` wrote (a .pfm is quantised as a PNG of it would be; a PNG with
// alpha, from --background transparent, is encoded as RGBA).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "bench/bench_common.h"
#include "bench/registry.h"
#include "common/error.h"
#include "common/file_util.h"
#include "common/timer.h"
#include "scene/image.h"
#include "scene/png_writer.h"

namespace sm::app::bench {
namespace {

struct PngArgs {
  std::string image, levels = "1,4,6,9", json, markdown;
  int runs = 5;
};

// The frame's 8-bit pixels as its PNG holds them: RGBA when some pixel is not opaque, else RGB.
std::vector<uint8_t> pixelsOf(const scene::Image& img, int& channels) {
  bool alpha = false;
  for (const glm::vec4& p : img.pixels) alpha = alpha || p.a < 1.0f;
  channels = alpha ? 4 : 3;
  std::vector<uint8_t> out;
  out.reserve(img.pixels.size() * size_t(channels));
  for (const glm::vec4& p : img.pixels)
    for (int c = 0; c < channels; ++c)
      out.push_back(uint8_t(std::lround(std::clamp(p[c], 0.0f, 1.0f) * 255.0f)));
  return out;
}

void runPngBench(const PngArgs& a) {
  if (a.runs < 1) throw Error("--runs: must be at least 1, not ", a.runs);
  const scene::Image img =
      fileExtension(a.image) == ".pfm" ? scene::readPfm(a.image) : scene::readPng(a.image);
  int channels = 3;
  const std::vector<uint8_t> px = pixelsOf(img, channels);
  struct Encoder {
    std::string name;
    std::function<std::vector<uint8_t>()> encode;
  };
  std::vector<Encoder> encoders = {
      {"stb_image_write",
       [&] { return scene::encodePngStb(px, img.width, img.height, channels); }}};
  for (const uint64_t level : parseCounts("--levels", a.levels)) {
    if (level > 9) throw Error("--levels: ", level, " is not a zlib level (0-9)");
    encoders.push_back(
        {concat("libpng level ", level, level == uint64_t(scene::kPngLevel) ? " (used)" : ""),
         [&, level] { return scene::encodePng(px, img.width, img.height, channels, int(level)); }});
  }
  nlohmann::json report = {{"image", a.image},
                           {"width", img.width},
                           {"height", img.height},
                           {"channels", channels},
                           {"runs", a.runs},
                           {"machine", machineJson()},
                           {"encoders", nlohmann::json::array()}};
  Table table({"encoder", "bytes", "vs stb", "encode ms (median)", "vs stb"});
  double stbBytes = 0, stbMs = 0;
  for (const Encoder& e : encoders) {
    std::vector<double> ms;
    size_t bytes = 0;
    for (int r = 0; r < a.runs; ++r) {
      Timer t;
      bytes = e.encode().size();
      ms.push_back(t.ms());
    }
    const double m = median(ms);
    if (stbBytes == 0) stbBytes = double(bytes), stbMs = m;
    report["encoders"].push_back(
        {{"name", e.name}, {"bytes", bytes}, {"ms", ms}, {"median_ms", m}});
    table.add({e.name, std::to_string(bytes), fixed(double(bytes) / stbBytes, 2), fixed(m, 1),
               fixed(m / stbMs, 2)});
  }
  const std::string text = concat("PNG encoding of ", a.image, " (", img.width, "x", img.height,
                                  channels == 4 ? ", RGBA" : ", RGB", "), median of ", a.runs,
                                  " runs\n", machineLine(report["machine"]), "\n\n", table.str());
  std::fputs(text.c_str(), stdout);
  if (!a.json.empty()) writeJsonFile(a.json, report);
  if (!a.markdown.empty()) writeTextFile(a.markdown, text);
}

}  // namespace

void configurePngBench(CLI::App& cmd) {
  auto a = std::make_shared<PngArgs>();
  cmd.add_option("image", a->image, "A frame render wrote (.png or .pfm), e.g. 1024x1024")
      ->required();
  cmd.add_option("--levels", a->levels, "libpng zlib levels to measure, comma separated")
      ->capture_default_str();
  cmd.add_option("--runs", a->runs, "Encodings per encoder (the median is reported)")
      ->capture_default_str();
  cmd.add_option("--json", a->json, "Write the results as JSON to this file");
  cmd.add_option("--markdown", a->markdown, "Write the table as Markdown to this file");
  cmd.callback([a] { runPngBench(*a); });
}

}  // namespace sm::app::bench
