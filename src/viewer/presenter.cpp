#include "viewer/presenter.h"

#include <algorithm>
#include <cmath>

#include "viewer/overlay.h"

namespace sm::view {
namespace {

// The same rounding as scene::writePng, so that the window shows a screenshot's bytes.
uint8_t toByte(float v) {
  if (!std::isfinite(v)) v = 0.0f;
  return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

VkExtent2D extentOf(const std::pair<int, int>& size) {
  return {uint32_t(std::max(size.first, 0)), uint32_t(std::max(size.second, 0))};
}

}  // namespace

void toDisplayBytes(const std::vector<glm::vec4>& pixels, const glm::vec3& background,
                    std::vector<uint8_t>& rgba) {
  rgba.resize(pixels.size() * 4);
  for (size_t i = 0; i < pixels.size(); ++i) {
    const glm::vec4& p = pixels[i];
    const glm::vec3 c = glm::vec3(p) + (1.0f - p.a) * background;
    rgba[4 * i] = toByte(c.r);
    rgba[4 * i + 1] = toByte(c.g);
    rgba[4 * i + 2] = toByte(c.b);
    rgba[4 * i + 3] = 255;
  }
}

Presenter::Presenter(Window& window, const vk::Context& ctx, const glm::vec3& background)
    : window_(window), background_(background) {
  fill_[0] = toByte(background.r);
  fill_[1] = toByte(background.g);
  fill_[2] = toByte(background.b);
  fill_[3] = 255;
  surface_ = window.createSurface(ctx);
  swapchain_ = std::make_unique<vk::Swapchain>(ctx, surface_, extentOf(window.framebufferSize()));
}

Presenter::~Presenter() {
  swapchain_.reset();  // before the surface it presents to
}

void Presenter::show(const std::vector<glm::vec4>& pixels, int width, int height,
                     const std::vector<std::string>& overlay) {
  toDisplayBytes(pixels, background_, rgba_);
  // Text at twice the font's size only where it leaves room for the picture.
  drawOverlay(rgba_, width, height, overlay, width >= 640 ? 2 : 1);
  const vk::HostImage image{rgba_, uint32_t(width), uint32_t(height)};
  // A resize can outdate the swapchain again while it is rebuilt: a few tries, then the next
  // frame tries again.
  for (int attempt = 0; attempt < 3; ++attempt) {
    const VkExtent2D want = extentOf(window_.framebufferSize());
    if (want.width == 0 || want.height == 0) return;
    const VkExtent2D have = swapchain_->extent();
    if (have.width != want.width || have.height != want.height) swapchain_->recreate(want);
    if (swapchain_->present(image, fill_) == vk::PresentResult::Presented) {
      ++presented_;
      return;
    }
    swapchain_->recreate(want);
  }
}

}  // namespace sm::view
