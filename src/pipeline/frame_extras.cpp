#include "pipeline/frame_extras.h"

#include <algorithm>
#include <cstdio>

#include "common/error.h"
#include "common/log.h"
#include "compositor/tools/count_dump.h"
#include "compositor/tools/image_compare.h"
#include "pipeline/render_options.h"
#include "scene/image.h"

namespace sm::app {
namespace {

void writeHeat(const std::string& path, const std::vector<glm::vec4>& rgba, int w, int h) {
  scene::Image img(w, h);
  img.pixels = rgba;
  scene::writePng(path, img, glm::vec3(0.0f));
}

// Composites the lists again with the other method and writes the per-pixel L2 difference.
void compareMethods(const RenderJob& job, comp::DeepCompositor& compositor,
                    const std::vector<glm::vec4>& image, const std::string& path,
                    comm::Communicator& comm) {
  const auto other = job.composite == comp::CompositeMethod::Deep
                         ? comp::CompositeMethod::SingleFragment
                         : comp::CompositeMethod::Deep;
  std::vector<glm::vec4> second = compositor.composite(other);
  if (comm.rank() != 0) return;
  std::vector<float> l2 = comp::l2Difference(image, second);
  double sum = 0, mx = 0;
  uint64_t visible = 0;
  for (float v : l2) {
    sum += v;
    mx = std::max<double>(mx, v);
    visible += v > 1.0f / 255.0f;
  }
  std::printf(
      "single-fragment vs deep compositing: L2 max %.4f, mean %.5f, %llu of %zu pixels differ by "
      "more "
      "than 1/255 (heatmap: %s)\n",
      mx, l2.empty() ? 0.0 : sum / double(l2.size()), (unsigned long long)visible, l2.size(),
      path.c_str());
  writeHeat(path, comp::heatmap(std::span<const float>(l2)), compositor.width(),
            compositor.height());
}

void writeCountHeatmaps(comp::DeepCompositor& compositor, const std::string& prefix,
                        comm::Communicator& comm) {
  std::vector<std::vector<uint32_t>> counts = compositor.gatherCounts();
  if (comm.rank() != 0) return;
  uint32_t mx = 1;
  for (const auto& r : counts)
    for (uint32_t c : r) mx = std::max(mx, c);
  std::vector<uint32_t> all = comp::sumCounts(counts);
  uint32_t allMax = std::max<uint32_t>(1, *std::max_element(all.begin(), all.end()));
  for (size_t r = 0; r < counts.size(); ++r)
    writeHeat(concat(prefix, "_rank", r, ".png"),
              comp::heatmap(std::span<const uint32_t>(counts[r]), float(mx)), compositor.width(),
              compositor.height());
  writeHeat(combinedHeatmapPath(prefix),
            comp::heatmap(std::span<const uint32_t>(all), float(allMax)), compositor.width(),
            compositor.height());
  log::info("wrote fragment-count heatmaps ", prefix, "_rank*.png and ", prefix, "_all.png (max ",
            allMax, " fragments per pixel)");
}

// The frame's counts for replaying the exchange at other rank counts (compositor/replay.h).
void dumpCounts(comp::DeepCompositor& compositor, const std::string& path) {
  uint32_t ranks = 0;
  try {
    ranks = comp::dumpFrameCounts(compositor, path);
  } catch (const std::runtime_error& e) {
    throw Error("--dump-counts: ", e.what());
  }
  if (ranks > 0) log::info("wrote the fragment counts of ", ranks, " rank(s) to ", path);
}

}  // namespace

std::string combinedHeatmapPath(const std::string& prefix) {
  return prefix + "_all.png";
}

std::string framePath(const std::string& out, uint64_t step, bool sequence) {
  if (!sequence) return out;
  std::string stem = out, ext;
  if (auto dot = out.rfind('.');
      dot != std::string::npos && out.find('/', dot) == std::string::npos) {
    stem = out.substr(0, dot);
    ext = out.substr(dot);
  }
  char num[16];
  std::snprintf(num, sizeof num, "_%04llu", (unsigned long long)step);
  return stem + num + ext;
}

void writeFrameExtras(const RenderJob& job, comp::DeepCompositor& compositor,
                      const std::vector<glm::vec4>& image, uint64_t step, bool sequence,
                      comm::Communicator& comm) {
  if (!job.l2Heatmap.empty())
    compareMethods(job, compositor, image, framePath(job.l2Heatmap, step, sequence), comm);
  if (!job.heatmaps.empty())
    writeCountHeatmaps(compositor, framePath(job.heatmaps, step, sequence), comm);
  if (!job.dumpCounts.empty()) dumpCounts(compositor, framePath(job.dumpCounts, step, sequence));
}

}  // namespace sm::app
