#include "viewer/screen_image.h"

#include <algorithm>
#include <cstdio>

namespace sm::view {

std::string numberedPath(const std::string& base, uint32_t frame) {
  std::string stem = base.empty() ? "shellmarch-view.png" : base, ext = ".png";
  if (auto dot = stem.rfind('.');
      dot != std::string::npos && stem.find('/', dot) == std::string::npos) {
    ext = stem.substr(dot);
    stem.resize(dot);
  }
  char num[16];
  std::snprintf(num, sizeof num, "_%04u", frame);
  return stem + num + ext;
}

void enlarge(const std::vector<glm::vec4>& small, int smallWidth, int smallHeight, int width,
             int height, std::vector<glm::vec4>& out) {
  out.resize(size_t(width) * size_t(height));
  for (int y = 0; y < height; ++y) {
    const int sy = std::min(smallHeight - 1, int(int64_t(y) * smallHeight / height));
    for (int x = 0; x < width; ++x) {
      const int sx = std::min(smallWidth - 1, int(int64_t(x) * smallWidth / width));
      out[size_t(y) * width + x] = small[size_t(sy) * smallWidth + sx];
    }
  }
}

}  // namespace sm::view
