#include "cli/image_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <ostream>

#include "cli/commands.h"
#include "common/error.h"
#include "common/file_util.h"

namespace sm::app {
namespace {

constexpr const char* kChannelNames[4] = {"R", "G", "B", "A"};

// A channel's value in 8-bit levels: a PNG's byte exactly (readPng stores byte / 255 as a float),
// a PFM's float times 255.
double level(float v, bool eightBit) {
  const double l = double(v) * 255.0;
  return eightBit ? std::round(l) : l;
}

double psnrOf(double rmse) {
  return rmse > 0 ? 20.0 * std::log10(255.0 / rmse) : std::numeric_limits<double>::infinity();
}

bool sameFile(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (std::filesystem::equivalent(a, b, ec)) return true;
  auto resolved = [](const std::string& p) {
    std::error_code e;
    return std::filesystem::weakly_canonical(std::filesystem::absolute(p, e), e);
  };
  return resolved(a) == resolved(b);
}

std::string number(double v, const char* format = "%.6g") {
  if (std::isinf(v)) return "inf";
  char text[32];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

template <typename Write>
void writeOutput(const std::string& option, Write write) {
  try {
    write();
  } catch (const Error& e) {
    throw UsageError(option, ": ", e.what());
  }
}

}  // namespace

CheckImage readCheckImage(const std::string& path, const std::string& role) {
  const std::string ext = fileExtension(path);
  if (ext != ".png" && ext != ".pfm")
    throw UsageError(role, ": '", path, "' must end in .png or .pfm");
  CheckImage in;
  in.path = path;
  in.eightBit = ext == ".png";
  try {
    in.image = in.eightBit ? scene::readPng(path) : scene::readPfm(path);
  } catch (const Error& e) {
    throw UsageError(e.what());  // names the file
  }
  return in;
}

ImageCheck checkImages(const CheckImage& result, const CheckImage& baseline,
                       const CheckTolerance& tolerance) {
  const scene::Image &a = result.image, &b = baseline.image;
  if (a.width != b.width || a.height != b.height)
    throw UsageError("'", result.path, "' is ", a.width, "x", a.height, " pixels but '",
                     baseline.path, "' is ", b.width, "x", b.height, ": images of different sizes");
  ImageCheck c;
  c.width = a.width;
  c.height = a.height;
  c.pixels = a.pixels.size();
  std::array<double, 4> sum{}, count{};
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    bool beyond = false, nonFinite = false;
    for (int ch = 0; ch < 4; ++ch) {
      const double x = level(a.pixels[i][ch], result.eightBit);
      const double y = level(b.pixels[i][ch], baseline.eightBit);
      if (!std::isfinite(x) || !std::isfinite(y)) {
        nonFinite = true;
        continue;
      }
      if (ch == 3 && (x != 255.0 || y != 255.0)) c.alphaInAll = true;
      const double d = std::abs(x - y);
      sum[ch] += d * d;
      count[ch] += 1;
      c.channels[ch].maxAbs = std::max(c.channels[ch].maxAbs, d);
      beyond |= d > tolerance.levels;
    }
    c.nonFinite += nonFinite;
    c.beyond += beyond || nonFinite;
  }
  double allSum = 0, allCount = 0;
  for (int ch = 0; ch < 4; ++ch) {
    ChannelError& e = c.channels[ch];
    e.rmse = count[ch] > 0 ? std::sqrt(sum[ch] / count[ch]) : 0.0;
    e.psnr = psnrOf(e.rmse);
    if (ch < 3 || c.alphaInAll) {
      allSum += sum[ch];
      allCount += count[ch];
      c.all.maxAbs = std::max(c.all.maxAbs, e.maxAbs);
    }
  }
  c.all.rmse = allCount > 0 ? std::sqrt(allSum / allCount) : 0.0;
  c.all.psnr = psnrOf(c.all.rmse);
  // As a share (a correctly rounded quotient), not beyond <= maxShare * pixels: 0.29 * 100 rounds
  // to 28.999..., which would fail 29 pixels of 100 against --max-share 0.29.
  c.passed = c.share() <= tolerance.maxShare;
  return c;
}

scene::Image checkDifferenceImage(const CheckImage& result, const CheckImage& baseline,
                                  const CheckTolerance& tolerance) {
  const scene::Image &a = result.image, &b = baseline.image;
  scene::Image d(a.width, a.height);
  for (size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i) {
    bool differs = false, beyond = false;
    glm::dvec4 la;
    for (int ch = 0; ch < 4; ++ch) {
      la[ch] = level(a.pixels[i][ch], result.eightBit);
      const double lb = level(b.pixels[i][ch], baseline.eightBit);
      const double diff = std::abs(la[ch] - lb);
      if (!std::isfinite(diff)) beyond = true;
      differs |= diff != 0;
      beyond |= diff > tolerance.levels;
    }
    if (beyond) {
      d.pixels[i] = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
    } else if (differs) {
      d.pixels[i] = glm::vec4(1.0f, 0.85f, 0.0f, 1.0f);
    } else {
      const double grey = std::clamp(0.299 * la.r + 0.587 * la.g + 0.114 * la.b, 0.0, 255.0);
      const float v = float((255.0 + (grey - 255.0) * 0.15) / 255.0);
      d.pixels[i] = glm::vec4(v, v, v, 1.0f);
    }
  }
  return d;
}

std::string defaultDiffPath(const std::string& result) {
  return std::filesystem::path(result).replace_extension(".diff.png").string();
}

void checkOutputNames(const CheckFiles& f) {
  const std::string diff = f.diff.empty() ? defaultDiffPath(f.result) : f.diff;
  if (fileExtension(diff) != ".png") throw UsageError("--diff: '", diff, "' must end in .png");
  for (const auto& [option, path] :
       {std::pair<std::string, std::string>{"--diff", diff}, {"--json", f.json}}) {
    if (path.empty()) continue;
    if (sameFile(path, f.result))
      throw UsageError(option, ": '", path, "' is also the file of ", f.resultRole);
    if (sameFile(path, f.baseline))
      throw UsageError(option, ": '", path, "' is also the file of ", f.baselineRole);
  }
  if (!f.json.empty() && sameFile(f.json, diff))
    throw UsageError("--json: '", f.json, "' is also the difference image");
}

std::string checkTable(const ImageCheck& c, const CheckFiles& f) {
  const std::string diff = f.diff.empty() ? defaultDiffPath(f.result) : f.diff;
  std::string t = concat("compare ", f.result, " against ", f.baseline, ": ", c.width, "x",
                         c.height, " pixels, differences in 8-bit levels (0..255)\n");
  char row[160];
  std::snprintf(row, sizeof row, "%-9s %12s %12s %10s\n", "channel", "max abs", "RMSE", "PSNR dB");
  t += row;
  auto line = [&](const std::string& name, const ChannelError& e) {
    std::snprintf(row, sizeof row, "%-9s %12s %12s %10s\n", name.c_str(), number(e.maxAbs).c_str(),
                  number(e.rmse).c_str(), number(e.psnr, "%.2f").c_str());
    t += row;
  };
  for (int ch = 0; ch < 4; ++ch) line(kChannelNames[ch], c.channels[ch]);
  line(c.alphaInAll ? "all" : "all (RGB)", c.all);
  t += concat("beyond tolerance ", number(f.tolerance.levels), ": ", c.beyond, " of ", c.pixels,
              " pixels (", number(100.0 * c.share()), "%), allowed ",
              number(100.0 * f.tolerance.maxShare), "% (--max-share ", number(f.tolerance.maxShare),
              ")\n");
  if (c.nonFinite > 0)
    t += concat("non-finite: ", c.nonFinite, " pixels (counted beyond the tolerance)\n");
  t += concat("difference image: ", diff, "\n");
  t += c.passed ? "passed: within the tolerance\n" : "FAILED: beyond the tolerance\n";
  return t;
}

nlohmann::ordered_json checkJson(const ImageCheck& c, const CheckFiles& f) {
  auto channel = [](const ChannelError& e) {
    nlohmann::ordered_json j;
    j["max_abs"] = e.maxAbs;
    j["rmse"] = e.rmse;
    j["psnr_db"] = std::isinf(e.psnr) ? nlohmann::ordered_json() : nlohmann::ordered_json(e.psnr);
    return j;
  };
  nlohmann::ordered_json j;
  j["result"] = f.result;
  j["baseline"] = f.baseline;
  j["width"] = c.width;
  j["height"] = c.height;
  j["units"] = "8-bit levels (0..255)";
  j["tolerance"] = f.tolerance.levels;
  j["max_share"] = f.tolerance.maxShare;
  for (int ch = 0; ch < 4; ++ch) j["channels"][kChannelNames[ch]] = channel(c.channels[ch]);
  j["channels"]["all"] = channel(c.all);
  j["all_includes_alpha"] = c.alphaInAll;
  j["pixels"] = c.pixels;
  j["beyond"] = c.beyond;
  j["beyond_share"] = c.share();
  j["non_finite"] = c.nonFinite;
  j["diff"] = f.diff.empty() ? defaultDiffPath(f.result) : f.diff;
  j["passed"] = c.passed;
  return j;
}

std::string checkFailure(const ImageCheck& c, const CheckFiles& f) {
  return concat("'", f.result, "' differs from '", f.baseline, "' beyond the tolerance: ", c.beyond,
                " of ", c.pixels, " pixels (", number(100.0 * c.share()),
                "%) differ by more than --tolerance ", number(f.tolerance.levels),
                c.nonFinite ? concat(" or are not finite (", c.nonFinite, ")") : std::string(),
                ", more than --max-share ", number(f.tolerance.maxShare), " allows");
}

ImageCheck runImageCheck(const CheckFiles& f, std::ostream& out) {
  checkOutputNames(f);
  const CheckImage result = readCheckImage(f.result, f.resultRole);
  const CheckImage baseline = readCheckImage(f.baseline, f.baselineRole);
  const ImageCheck check = checkImages(result, baseline, f.tolerance);
  const std::string diff = f.diff.empty() ? defaultDiffPath(f.result) : f.diff;
  const scene::Image image = checkDifferenceImage(result, baseline, f.tolerance);
  writeOutput("--diff", [&] { scene::writePng(diff, image, glm::vec3(0.0f)); });
  if (!f.json.empty()) {
    const std::string text = checkJson(check, f).dump(2) + "\n";
    writeOutput("--json", [&] {
      writeBytesAtomically(f.json, {reinterpret_cast<const uint8_t*>(text.data()), text.size()});
    });
  }
  out << checkTable(check, f) << std::flush;
  return check;
}

std::pair<CLI::Option*, CLI::Option*> addToleranceOptions(CLI::App* cmd,
                                                          CheckTolerance& tolerance) {
  // Checked as text, before CLI11 converts it: its conversion takes "nan" and "inf".
  auto amount = [](double hi, const char* name, const char* above) {
    return CLI::Validator(
        [hi, above](std::string& s) -> std::string {
          char* end = nullptr;
          const double v = std::strtod(s.c_str(), &end);
          if (s.empty() || end != s.c_str() + s.size()) return "'" + s + "' is not a number";
          if (!std::isfinite(v)) return "'" + s + "' is not a finite number";
          if (v < 0) return "'" + s + "' is negative";
          if (v > hi) return "'" + s + "' is " + above;
          return {};
        },
        name);
  };
  const double any = std::numeric_limits<double>::max();
  CLI::Option* t =
      cmd->add_option("--tolerance", tolerance.levels,
                      "Largest difference of a channel (R, G, B or A) that passes, in 8-bit "
                      "levels 0..255 (a PFM's 1.0 is 255) (default 0: equal)")
          ->check(amount(any, "LEVELS", ""));
  CLI::Option* s =
      cmd->add_option("--max-share", tolerance.maxShare,
                      "Fraction of the pixels (0..1) that may be beyond --tolerance (default 0)")
          ->check(amount(1.0, "FRACTION", "more than 1 (a fraction of the pixels)"));
  return {t, s};
}

}  // namespace sm::app
