#pragma once

#include <span>
#include <string_view>

namespace sm::scene {

// A built-in colour map: 256 RGB entries in [0, 1].
struct ColormapData {
  std::string_view name;
  const float* rgb;
};

std::span<const ColormapData> builtinColormaps();

}  // namespace sm::scene
