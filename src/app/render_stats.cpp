#include "app/render_stats.h"

#include <algorithm>
#include <cstdio>

#include "app/render_job.h"
#include "common/error.h"
#include "common/file_util.h"
#include "common/log.h"
#include "prep/memory_report.h"

namespace sm::app {

PixelCountSummary summarise(const std::vector<uint32_t>& counts) {
  PixelCountSummary s;
  uint64_t sum = 0;
  for (uint32_t c : counts) {
    s.max = std::max(s.max, c);
    if (c) {
      ++s.nonEmpty;
      sum += c;
    }
  }
  s.total = sum;
  s.meanNonEmpty = s.nonEmpty ? double(sum) / double(s.nonEmpty) : 0.0;
  return s;
}

StatsReport::StatsReport(const RenderJob& job, Collectives& coll) : job_(job), coll_(coll) {
  json_["mesh"] = job.mesh;
  json_["ranks"] = coll.size();
  json_["width"] = job.width;
  json_["height"] = job.height;
  json_["frames"] = nlohmann::json::array();
}

void StatsReport::setSetup(double loadSeconds, double prepSeconds, bool fromCache, const prep::PreparedRank& rank,
                           const render::GpuScene& gpu, const std::string& device, const render::RenderSettings& s) {
  auto mem = prep::memoryReport(rank);
  mem.accelerationStructures = gpu.accelerationStructureBytes();
  json_["device"] = device;
  json_["dt"] = s.dt;
  json_["load_seconds_max"] = coll_.max(loadSeconds);
  json_["prepare_seconds_max"] = coll_.max(prepSeconds);
  json_["prepare_from_cache"] = fromCache;
  json_["elements"] = coll_.sum(rank.numElements());
  json_["elements_max_rank"] = coll_.max(double(rank.numElements()));
  json_["shell_triangles"] = coll_.sum(rank.numShellTriangles());
  json_["shell_triangles_max_rank"] = coll_.max(double(rank.numShellTriangles()));
  json_["device_bytes_max_rank"] = coll_.max(double(gpu.deviceBytes()));
  json_["memory_rank0"] = mem;
}

void StatsReport::addFrame(uint64_t step, const render::FrameResult& f, const render::Renderer& renderer) {
  // Per-pixel counts cost a download per frame: only when statistics are asked for.
  const bool wanted = job_.stats || !job_.statsJson.empty();
  PixelCountSummary seg = wanted ? summarise(renderer.lastSegmentCounts()) : PixelCountSummary{};
  PixelCountSummary frag = wanted ? summarise(renderer.lastFragmentCounts()) : PixelCountSummary{};
  nlohmann::json fr;
  fr["step"] = step;
  fr["total_ms"] = coll_.max(f.timings.totalMs);
  fr["traversal_ms"] = coll_.max(f.timings.traversalMs);
  fr["scan_ms"] = coll_.max(f.timings.scanMs);
  fr["march_ms"] = coll_.max(f.timings.marchMs);
  fr["composite_ms"] = coll_.max(f.timings.compositeMs);
  fr["segments"] = coll_.sum(uint64_t(f.counters.segments));
  fr["fragments"] = coll_.sum(uint64_t(f.counters.fragments));
  fr["segments_per_pixel_mean_rank0"] = seg.meanNonEmpty;
  fr["segments_per_pixel_max"] = coll_.max(double(seg.max));
  fr["fragments_per_pixel_mean_rank0"] = frag.meanNonEmpty;
  fr["fragments_per_pixel_max"] = coll_.max(double(frag.max));
  fr["lost_rays"] = coll_.sum(uint64_t(f.counters.lostRays));
  fr["grazing_skips"] = coll_.sum(uint64_t(f.counters.grazingSkips));
  fr["entry_corrections"] = coll_.sum(uint64_t(f.counters.entryWalks));
  fr["step_limit_hits"] = coll_.sum(uint64_t(f.counters.stepLimitHits));
  fr["fragment_overflow"] = coll_.sum(uint64_t(f.counters.overflow));
  fr["samples"] = coll_.sum(uint64_t(f.counters.samples));
  fr["element_steps"] = coll_.sum(uint64_t(f.counters.elementSteps));
  fr["camera_inside_rays"] = coll_.sum(uint64_t(f.counters.cameraInside));
  json_["frames"].push_back(fr);
}

void StatsReport::finish(uint64_t validationErrors) {
  uint64_t errors = coll_.sum(validationErrors);
  json_["validation_errors"] = errors;
  if (coll_.rank() == 0 && job_.stats) {
    const auto& j = json_;
    std::printf("shellmarch render: %s on %s, %d rank(s), %dx%d, dt %.4g\n", job_.mesh.c_str(),
                j["device"].get<std::string>().c_str(), coll_.size(), job_.width, job_.height, j["dt"].get<double>());
    std::printf("  load %.2f s, prepare %.2f s%s; %llu elements, %llu shell triangles\n",
                j["load_seconds_max"].get<double>(), j["prepare_seconds_max"].get<double>(),
                j["prepare_from_cache"].get<bool>() ? " (from cache)" : "",
                (unsigned long long)j["elements"].get<uint64_t>(), (unsigned long long)j["shell_triangles"].get<uint64_t>());
    for (const auto& fr : j["frames"]) {
      std::printf("  step %llu: %.1f ms = traversal %.1f + scan %.1f + march %.1f + composite %.1f\n",
                  (unsigned long long)fr["step"].get<uint64_t>(), fr["total_ms"].get<double>(),
                  fr["traversal_ms"].get<double>(), fr["scan_ms"].get<double>(), fr["march_ms"].get<double>(),
                  fr["composite_ms"].get<double>());
      std::printf("    segments/pixel mean %.2f max %.0f; fragments/pixel mean %.2f max %.0f (non-empty pixels)\n",
                  fr["segments_per_pixel_mean_rank0"].get<double>(), fr["segments_per_pixel_max"].get<double>(),
                  fr["fragments_per_pixel_mean_rank0"].get<double>(), fr["fragments_per_pixel_max"].get<double>());
      std::printf("    lost rays %llu, grazing %llu, entry corrections %llu, step-limit hits %llu, overflow %llu; "
                  "%llu samples, %llu element steps\n",
                  (unsigned long long)fr["lost_rays"].get<uint64_t>(), (unsigned long long)fr["grazing_skips"].get<uint64_t>(),
                  (unsigned long long)fr["entry_corrections"].get<uint64_t>(),
                  (unsigned long long)fr["step_limit_hits"].get<uint64_t>(),
                  (unsigned long long)fr["fragment_overflow"].get<uint64_t>(),
                  (unsigned long long)fr["samples"].get<uint64_t>(), (unsigned long long)fr["element_steps"].get<uint64_t>());
    }
  }
  // Fixed-length lists lose what does not fit (dropped or merged out of order): the image is
  // then approximate, which must be said whether or not --stats was asked for.
  uint64_t overflow = 0, overflowFrames = 0;
  for (const auto& fr : json_["frames"]) {
    overflow += fr["fragment_overflow"].get<uint64_t>();
    overflowFrames += fr["fragment_overflow"].get<uint64_t>() > 0;
  }
  json_["fragment_overflow"] = overflow;
  if (coll_.rank() == 0 && overflow > 0)
    log::warning(
        "fixed-length fragment lists (--k ", job_.lists.fixedK, ") overflowed: ", overflow,
        " fragments ", job_.lists.mode == comp::ListMode::FixedMerge ? "merged" : "dropped", " in ",
        overflowFrames, " of ", json_["frames"].size(),
        " frame(s), so the image is approximate; use a larger --k, or --lists two-pass (exact)");
  if (coll_.rank() == 0 && !job_.statsJson.empty()) {
    std::string text = json_.dump(2) + "\n";
    writeBytesAtomically(job_.statsJson, {reinterpret_cast<const uint8_t*>(text.data()), text.size()});
  }
  if (errors) throw Error("the Vulkan validation layer reported ", errors, " error(s)");
}

}  // namespace sm::app
