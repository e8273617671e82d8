// image_diff A B [--max-abs X] [--max-rmse X] [--min-max-abs X]: compares two images (.pfm or .png)
// channel by channel and exits non-zero when a bound is broken. --min-max-abs asks that they
// differ (by at least X somewhere): used to show that single-fragment compositing is visibly wrong.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "common/file_util.h"
#include "scene/image.h"

using namespace sm;

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: image_diff A B [--max-abs X] [--max-rmse X] [--min-max-abs X]\n");
    return 2;
  }
  double maxAbs = -1, maxRmse = -1, minMaxAbs = -1;
  for (int i = 3; i + 1 < argc; i += 2) {
    double v = std::atof(argv[i + 1]);
    if (!std::strcmp(argv[i], "--max-abs"))
      maxAbs = v;
    else if (!std::strcmp(argv[i], "--max-rmse"))
      maxRmse = v;
    else if (!std::strcmp(argv[i], "--min-max-abs"))
      minMaxAbs = v;
  }
  auto load = [](const char* p) {
    return fileExtension(p) == ".pfm" ? scene::readPfm(p) : scene::readPng(p);
  };
  try {
    scene::Image a = load(argv[1]), b = load(argv[2]);
    scene::ImageError e = scene::compareImages(a, b);
    int differing = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c)
        differing += std::abs(a.pixels[i][c] - b.pixels[i][c]) > 1.0f / 255.0f;
    std::printf(
        "%s vs %s: RMSE %.3g, max abs %.3g, PSNR %.1f dB, %d channel values differ by more than "
        "1/255\n",
        argv[1], argv[2], e.rmse, e.maxAbs, e.psnr, differing);
    bool ok = e.nanPixels == 0 && (maxAbs < 0 || e.maxAbs <= maxAbs) &&
              (maxRmse < 0 || e.rmse <= maxRmse) && (minMaxAbs < 0 || e.maxAbs >= minMaxAbs);
    if (!ok)
      std::printf("FAILED bounds: max-abs %g max-rmse %g min-max-abs %g\n", maxAbs, maxRmse,
                  minMaxAbs);
    return ok ? 0 : 1;
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "image_diff: %s\n", ex.what());
    return 2;
  }
}
