// Rank 0's output: the composited frame over the background, with the overlay, copied into the
// window's swapchain. Handles out-of-date swapchains (resize) by rebuilding and presenting again.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "viewer/window.h"
#include "vk/present/swapchain.h"

namespace sm::view {

// Premultiplied RGBA over `background` as 8-bit RGBA, rounded as PNGs from `render` are.
void toDisplayBytes(const std::vector<glm::vec4>& pixels, const glm::vec3& background,
                    std::vector<uint8_t>& rgba);

class Presenter {
 public:
  Presenter(Window& window, const vk::Context& ctx, const glm::vec3& background);
  ~Presenter();

  // Shows a width x height frame with `overlay` lines (none when empty). A minimised window shows
  // nothing.
  void show(const std::vector<glm::vec4>& pixels, int width, int height,
            const std::vector<std::string>& overlay);
  uint64_t presented() const { return presented_; }
  uint64_t swapchainRebuilds() const { return swapchain_ ? swapchain_->recreations() : 0; }
  // The bytes last presented (with the overlay), width x height.
  const std::vector<uint8_t>& lastBytes() const { return rgba_; }

 private:
  Window& window_;
  glm::vec3 background_;
  uint8_t fill_[4];
  vk::Surface surface_;
  std::unique_ptr<vk::Swapchain> swapchain_;
  std::vector<uint8_t> rgba_;
  uint64_t presented_ = 0;
};

}  // namespace sm::view
