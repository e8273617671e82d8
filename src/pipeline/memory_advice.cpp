#include "pipeline/memory_advice.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "prep/memory_report.h"
#include "render/gpu_scene.h"

namespace sm::app {
namespace {

// Share of the device a suggestion plans for: the rest is left to what the estimates do not count
// (pipelines, staging, the compositor's exchange buffers on several ranks).
constexpr double kUsable = 0.8;
// The compositor's buffers grow to a quarter more than they must hold (compositor/device_util.h).
constexpr double kGrowth = 1.25;
// Bytes per pixel on every rank whatever the lists hold: capacities, offsets and counts (4 bytes
// each) and the composited image (16).
constexpr double kPixelBytes = (12 + 16) * kGrowth;

std::string bytes(double b) {
  return b >= double(UINT64_MAX) ? std::string("unlimited") : prep::formatBytes(uint64_t(b));
}

}  // namespace

std::string sceneMemoryAdvice(const vk::DeviceMemoryError& e, const vk::Context& ctx,
                              const prep::PreparedRank& rank, int ranks) {
  const double limit = double(ctx.deviceMemoryLimit());
  const double needed = double(render::GpuScene::requiredBytes(ctx, rank));
  // A scene shrinks with the share of the mesh a rank holds.
  const int fit = std::max(ranks + 1, int(std::ceil(needed * ranks / (kUsable * limit))));
  return concat("out of device memory for the scene (", e.what(), "): this rank's ",
                rank.numElements(), " elements and ", rank.numShellTriangles(),
                " shell triangles need about ", bytes(needed),
                " while the acceleration structure is built, the device allows ", bytes(limit),
                "; what would fit: about ", fit, " ranks (mpiexec -n ", fit, ")");
}

std::string listMemoryAdvice(const vk::DeviceMemoryError& e, const vk::Context& ctx,
                             uint64_t sceneBytes, int width, int height,
                             const comp::CompositorOptions& lists, int ranks) {
  const double limit = double(ctx.deviceMemoryLimit());
  const double pixels = double(width) * double(height);
  const double slot = comp::fragmentBytes(lists.encoding) * kGrowth;
  const double scene = double(sceneBytes);
  const double room = std::max(0.0, kUsable * limit - scene);
  const bool fixed = lists.mode != comp::ListMode::TwoPass;
  // What the lists held when the allocation failed, plus that allocation, is a lower bound; fixed
  // lists are also known in advance (K slots per pixel on every rank).
  const double held = double(e.inUse()) > scene ? double(e.inUse()) - scene : 0.0;
  double needed = std::max(held + double(e.requested()), pixels * kPixelBytes);
  if (fixed) needed = std::max(needed, pixels * (kPixelBytes + lists.fixedK * slot));

  std::string fits;
  auto add = [&](const std::string& s) { fits += (fits.empty() ? "" : ", or ") + s; };
  const int64_t k = int64_t((room / pixels - kPixelBytes) / slot);
  if (k >= 1 && (!fixed || uint64_t(k) < lists.fixedK))
    add(concat(fixed ? "" : "--lists drop ", "--k ", std::min<int64_t>(k, 64)));
  // Everything here grows with the pixel count.
  const double scale = std::sqrt(room / needed);
  const int w = int(width * scale), h = int(height * scale);
  if (scale < 1 && w >= 1 && h >= 1) add(concat("--size ", w, "x", h));
  // More ranks shrink only a rank's share of two-pass fragments; the per-pixel buffers stay.
  const double perPixel = pixels * kPixelBytes, spread = needed - perPixel;
  if (!fixed && room > perPixel && spread > 0) {
    const int n = std::max(ranks + 1, int(std::ceil(spread * ranks / (room - perPixel))));
    add(concat("about ", n, " ranks (mpiexec -n ", n, ")"));
  }
  if (fits.empty()) fits = "nothing smaller: the device cannot hold the scene and an image";
  return concat("out of device memory for fragment lists (", e.what(), "): ", width, "x", height,
                " pixels with ",
                fixed ? concat("--k ", lists.fixedK) : std::string("two-pass lists"),
                " need at least ", bytes(needed), " beside the scene's ", bytes(scene),
                ", the device allows ", bytes(limit), "; what would fit: ", fits,
                fixed ? " (more ranks do not shrink fixed-length lists)" : "");
}

}  // namespace sm::app
