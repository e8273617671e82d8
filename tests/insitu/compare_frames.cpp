// Compares the frames two runs of the in-situ example wrote (e.g. 1 and 3 MPI ranks): the same
// frame names in both folders, float images (.rgba) within a maximum absolute difference, PNGs
// within one 8-bit level, and something visible in every frame.
//   compare_frames DIR_A DIR_B MAX_ABS
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "scene/image.h"

namespace fs = std::filesystem;

namespace {

struct Raw {
  int width = 0, height = 0;
  std::vector<float> rgba;
};

Raw readRaw(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  Raw r;
  int32_t size[2] = {0, 0};
  f.read(reinterpret_cast<char*>(size), sizeof size);
  r.width = size[0];
  r.height = size[1];
  r.rgba.resize(size_t(r.width) * r.height * 4);
  f.read(reinterpret_cast<char*>(r.rgba.data()), std::streamsize(r.rgba.size() * 4));
  if (!f || r.rgba.empty()) throw std::runtime_error(p.string() + ": not a complete .rgba frame");
  return r;
}

std::set<std::string> frames(const fs::path& dir) {
  std::set<std::string> stems;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".rgba") stems.insert(e.path().stem().string());
  return stems;
}

// Returns the number of problems found with one frame.
int compareFrame(const fs::path& a, const fs::path& b, const std::string& stem, double maxAbs) {
  Raw ra = readRaw(a / (stem + ".rgba")), rb = readRaw(b / (stem + ".rgba"));
  if (ra.width != rb.width || ra.height != rb.height) {
    std::printf("%s: sizes differ\n", stem.c_str());
    return 1;
  }
  double err = 0, alpha = 0;
  for (size_t i = 0; i < ra.rgba.size(); ++i) {
    double d = std::abs(double(ra.rgba[i]) - rb.rgba[i]);
    err = std::isfinite(d) ? std::max(err, d) : INFINITY;
    if (i % 4 == 3) alpha = std::max(alpha, double(ra.rgba[i]));
  }
  sm::scene::ImageError png = sm::scene::compareImages(sm::scene::readPng(a / (stem + ".png")),
                                                       sm::scene::readPng(b / (stem + ".png")));
  std::printf("%s: float max abs %.3g (limit %.3g), PNG max abs %.3g, max opacity %.3f\n",
              stem.c_str(), err, maxAbs, png.maxAbs, alpha);
  return (err > maxAbs) + (png.maxAbs > 1.0 / 255 + 1e-6) + (alpha < 0.2);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: compare_frames DIR_A DIR_B MAX_ABS\n");
    return 2;
  }
  const fs::path a = argv[1], b = argv[2];
  const double maxAbs = std::atof(argv[3]);
  try {
    std::set<std::string> fa = frames(a), fb = frames(b);
    if (fa.empty() || fa != fb) {
      std::printf("frame sets differ or are empty: %zu in %s, %zu in %s\n", fa.size(), argv[1],
                  fb.size(), argv[2]);
      return 1;
    }
    int problems = 0;
    for (const std::string& stem : fa) problems += compareFrame(a, b, stem, maxAbs);
    std::printf("compare_frames: %zu frames, %s\n", fa.size(), problems ? "FAILED" : "passed");
    return problems ? 1 : 0;
  } catch (const std::exception& e) {
    std::printf("compare_frames: %s\n", e.what());
    return 1;
  }
}
