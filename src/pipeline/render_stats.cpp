#include "pipeline/render_stats.h"

#include <algorithm>
#include <cstdio>

#include "common/error.h"
#include "common/file_util.h"
#include "common/log.h"
#include "common/memory.h"
#include "common/parallel.h"
#include "pipeline/render_options.h"
#include "pipeline/sequence_stats.h"
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

StatsReport::StatsReport(const RenderJob& job, comm::Communicator& comm) : job_(job), comm_(comm) {
  json_["version"] = SHELLMARCH_VERSION;
  const ThreadBudget threads = threadBudget();  // rank 0's: ranks of one node take the same
  json_["threads"] = {{"per_rank", threads.threads}, {"from", threads.reason}};
  json_["mesh"] = job.mesh;
  json_["ranks"] = comm.size();
  json_["width"] = job.width;
  json_["height"] = job.height;
  json_["pixel_ownership"] = comp::ownershipName(job.lists.ownership);
  json_["frames"] = nlohmann::json::array();
}

nlohmann::json StatsReport::spread(double v) const {
  return nlohmann::json{{"min", comm::minOf(comm_, v)},
                        {"max", comm::maxOf(comm_, v)},
                        {"avg", comm::sumOf(comm_, v) / comm_.size()}};
}

void StatsReport::setSetup(double loadSeconds, double prepSeconds, bool fromCache,
                           const prep::PreparedRank& rank, const render::GpuScene& gpu,
                           const std::string& device, const std::string& tracer,
                           const render::RenderSettings& s) {
  auto mem = prep::memoryReport(rank);
  mem.accelerationStructures = gpu.accelerationStructureBytes();
  json_["device"] = device;
  json_["tracer"] = tracer;
  json_["integration"] = s.integration == render::Integration::Sampled ? "sampled" : "exact";
  json_["dt"] = s.dt;
  json_["clip_planes"] = nlohmann::json::array();
  for (const scene::ClipPlane& p : s.clipPlanes)
    json_["clip_planes"].push_back({{"point", {p.point.x, p.point.y, p.point.z}},
                                    {"normal", {p.normal.x, p.normal.y, p.normal.z}}});
  json_["log_scale"] = s.transferFunction.scale == scene::ScalarScale::Log;
  json_["opacity_points"] = nlohmann::json::array();
  for (const scene::OpacityPoint& p : job_.opacityPoints)
    json_["opacity_points"].push_back({p.value, p.opacity});
  json_["load_seconds_max"] = comm::maxOf(comm_, loadSeconds);
  json_["prepare_seconds_max"] = comm::maxOf(comm_, prepSeconds);
  json_["prepare_from_cache"] = fromCache;
  json_["elements"] = comm::sumOf(comm_, rank.numElements());
  json_["elements_per_rank"] = spread(double(rank.numElements()));
  json_["elements_rank0"] = rank.numElements();
  json_["shell_triangles"] = comm::sumOf(comm_, rank.numShellTriangles());
  json_["shell_triangles_per_rank"] = spread(double(rank.numShellTriangles()));
  json_["device_bytes_max_rank"] = comm::maxOf(comm_, double(gpu.deviceBytes()));
  json_["memory_rank0"] = mem;
  preparedBytes_ = mem.preparedBytes();
}

void StatsReport::setStartup(const vk::Context& ctx, double firstFrameMs,
                             double firstFrameDeviceMs) {
  const vk::PipelineStore& store = ctx.pipelines();
  double pipelinesMs = 0;
  uint64_t fromCache = 0;
  nlohmann::json list = nlohmann::json::array();
  for (const vk::PipelineTiming& t : store.timings()) {
    pipelinesMs += t.ms;
    fromCache += t.fromCache;
    list.push_back({{"name", t.name}, {"ms", t.ms}, {"from_cache", t.fromCache}});
  }
  nlohmann::json j;
  j["context_ms"] = comm::maxOf(comm_, ctx.creationMs());
  j["pipelines_ms"] = comm::maxOf(comm_, pipelinesMs);
  j["pipelines_rank0"] = list;
  j["pipelines_from_cache_rank0"] = fromCache;
  j["cache_folder"] = store.files().folder();
  j["shader_objects"] = store.shaderObjects();
  j["cache_files_rejected"] = comm::sumOf(comm_, store.files().rejected());
  j["first_frame_ms"] = comm::maxOf(comm_, firstFrameMs);
  j["first_frame_device_ms"] = comm::maxOf(comm_, firstFrameDeviceMs);
  json_["startup"] = j;
}

void StatsReport::setHostMemory(uint64_t residentAtStart, uint64_t peakAfterLoad,
                                uint64_t peakAfterPrepare) {
  json_["host_bytes_at_start_per_rank"] = spread(double(residentAtStart));
  json_["host_peak_bytes_after_prepare_per_rank"] = spread(double(peakAfterPrepare));
  // What reading and preparing held beyond the process's start, over this rank's own prepared
  // bytes: ranks hold unequal shares, so a ratio of maxima would mix ranks.
  json_["prepared_bytes_per_rank"] = spread(double(preparedBytes_));
  const double grown = double(peakAfterPrepare) - double(residentAtStart);
  json_["host_mesh_peak_over_prepared_per_rank"] =
      spread(preparedBytes_ ? grown / double(preparedBytes_) : 0.0);
  const double now = double(peakResidentBytes());
  json_["host_peak_bytes_after_load_per_rank"] = spread(double(peakAfterLoad));
  json_["host_peak_bytes_after_setup_per_rank"] = spread(now);
}

void StatsReport::setUpload(double seconds) {
  json_["scene_upload_seconds_max"] = comm::maxOf(comm_, seconds);
}

void StatsReport::setFrameMemory(const char* key) {
  if (wanted()) json_[key] = spread(double(currentResidentBytes()));
}

bool StatsReport::wanted() const {
  return job_.stats || !job_.statsJson.empty();
}

void StatsReport::addFrame(uint64_t step, const scene::Camera& camera, const render::FrameResult& f,
                           const render::Renderer& renderer, comp::DeepCompositor& compositor) {
  const uint64_t overflow = comm::sumOf(comm_, uint64_t(f.counters.overflow));
  overflow_ += overflow;
  overflowFrames_ += overflow > 0;
  frames_ += 1;
  if (!wanted()) return;  // per-pixel counts cost a download and a gather per frame
  PixelCountSummary seg = summarise(renderer.lastSegmentCounts());
  PixelCountSummary frag = summarise(renderer.lastFragmentCounts());
  std::vector<comp::CompositeStats> ranks = compositor.gatherStats();
  nlohmann::json fr;
  fr["frame"] = frames_ - 1;  // images are written for the first run only: its frame index
  fr["step"] = step;
  fr["eye"] = {camera.eye.x, camera.eye.y, camera.eye.z};
  fr["total_ms"] = comm::maxOf(comm_, f.timings.totalMs);
  fr["traversal_ms"] = comm::maxOf(comm_, f.timings.traversalMs);
  fr["scan_ms"] = comm::maxOf(comm_, f.timings.scanMs);
  fr["march_ms"] = comm::maxOf(comm_, f.timings.marchMs);
  fr["composite_ms"] = comm::maxOf(comm_, f.timings.compositeMs);
  fr["segments"] = comm::sumOf(comm_, uint64_t(f.counters.segments));
  fr["fragments"] = comm::sumOf(comm_, uint64_t(f.counters.fragments));
  fr["segments_per_pixel_mean_rank0"] = seg.meanNonEmpty;
  fr["segments_per_pixel_max"] = comm::maxOf(comm_, double(seg.max));
  fr["fragments_per_pixel_mean_rank0"] = frag.meanNonEmpty;
  fr["fragments_per_pixel_max"] = comm::maxOf(comm_, double(frag.max));
  fr["lost_rays"] = comm::sumOf(comm_, uint64_t(f.counters.lostRays));
  fr["grazing_skips"] = comm::sumOf(comm_, uint64_t(f.counters.grazingSkips));
  fr["entry_corrections"] = comm::sumOf(comm_, uint64_t(f.counters.entryWalks));
  fr["step_limit_hits"] = comm::sumOf(comm_, uint64_t(f.counters.stepLimitHits));
  fr["fragment_overflow"] = overflow;
  fr["samples"] = comm::sumOf(comm_, gpu::sampleCount(f.counters));
  fr["element_steps"] = comm::sumOf(comm_, gpu::elementStepCount(f.counters));
  fr["camera_inside_rays"] = comm::sumOf(comm_, uint64_t(f.counters.cameraInside));
  fr["box_exits"] = comm::sumOf(comm_, uint64_t(f.counters.boxExits));
  fr["shell_queries"] = comm::sumOf(comm_, uint64_t(f.counters.shellQueries));
  fr["cache_retraces"] = comm::sumOf(comm_, uint64_t(f.counters.cacheRetraces));
  fr["fused"] = f.timings.fused;
  // Integration (traversal + marching) against compositing, slowest rank each.
  fr["integration_ms"] =
      comm::maxOf(comm_, f.timings.traversalMs + f.timings.scanMs + f.timings.marchMs);
  fr["compositing_ms"] = comm::maxOf(comm_, f.timings.compositeMs);
  nlohmann::json perRank = nlohmann::json::array();
  for (size_t r = 0; r < ranks.size(); ++r)
    perRank.push_back({{"rank", r},
                       {"fragments", ranks[r].fragments},
                       {"fragments_per_nonempty_pixel", ranks[r].fragmentsPerNonEmptyPixel()},
                       {"bytes_sent", ranks[r].bytesSent},
                       {"count_bytes_sent", ranks[r].countBytesSent},
                       {"fragment_bytes_sent", ranks[r].fragmentBytesSent},
                       {"counter_bits", ranks[r].counterBits},
                       {"fragments_composited", ranks[r].fragmentsComposited},
                       {"composite_ms", ranks[r].milliseconds}});
  fr["ranks"] = perRank;
  json_["frames"].push_back(fr);
}

void StatsReport::printSetup() const {
  const auto& j = json_;
  std::printf("shellmarch render: %s on %s (%s tracer), %d rank(s), %dx%d, dt %.4g\n",
              job_.mesh.c_str(), j["device"].get<std::string>().c_str(),
              j["tracer"].get<std::string>().c_str(), comm_.size(), job_.width, job_.height,
              j["dt"].get<double>());
  std::printf("  load %.2f s, prepare %.2f s%s; %llu elements, %llu shell triangles\n",
              j["load_seconds_max"].get<double>(), j["prepare_seconds_max"].get<double>(),
              j["prepare_from_cache"].get<bool>() ? " (from cache)" : "",
              (unsigned long long)j["elements"].get<uint64_t>(),
              (unsigned long long)j["shell_triangles"].get<uint64_t>());
  if (j.contains("host_peak_bytes_after_load_per_rank")) {
    const double mib = 1024.0 * 1024.0;
    std::printf(
        "  memory, largest rank: host peak %.1f MiB after loading, %.1f MiB after setup (with the "
        "driver's); device %.1f MiB\n",
        j["host_peak_bytes_after_load_per_rank"]["max"].get<double>() / mib,
        j["host_peak_bytes_after_setup_per_rank"]["max"].get<double>() / mib,
        j["device_bytes_max_rank"].get<double>() / mib);
  }
  if (comm_.size() > 1) {
    const auto &e = j["elements_per_rank"], &sh = j["shell_triangles_per_rank"];
    std::printf(
        "  per rank: elements min %.0f max %.0f avg %.0f; shell triangles min %.0f max %.0f avg "
        "%.0f\n",
        e["min"].get<double>(), e["max"].get<double>(), e["avg"].get<double>(),
        sh["min"].get<double>(), sh["max"].get<double>(), sh["avg"].get<double>());
  }
}

void StatsReport::printStartup() const {
  if (!json_.contains("startup")) return;
  const auto& j = json_["startup"];
  const auto& list = j["pipelines_rank0"];
  const std::string folder = j["cache_folder"].get<std::string>();
  std::printf(
      "  startup: context %.0f ms; %zu pipelines in %.0f ms, %llu from the shader cache (%s%s); "
      "first frame %.0f ms, tracing on the device %.0f ms (slowest rank)\n",
      j["context_ms"].get<double>(), list.size(), j["pipelines_ms"].get<double>(),
      (unsigned long long)j["pipelines_from_cache_rank0"].get<uint64_t>(),
      folder.empty() ? "none" : folder.c_str(),
      j["shader_objects"].get<bool>() ? ", shader objects" : ", pipelines",
      j["first_frame_ms"].get<double>(), j["first_frame_device_ms"].get<double>());
  std::string line = "    pipelines (rank 0):";
  for (size_t i = 0; i < list.size(); ++i) {
    char item[160];
    std::snprintf(item, sizeof item, "%s %s %.1f ms%s", i ? "," : "",
                  list[i]["name"].get<std::string>().c_str(), list[i]["ms"].get<double>(),
                  list[i]["from_cache"].get<bool>() ? " (cached)" : "");
    line += item;
  }
  std::printf("%s\n", line.c_str());
}

void StatsReport::printFrame(const nlohmann::json& fr) const {
  auto u = [&](const char* k) { return (unsigned long long)fr[k].get<uint64_t>(); };
  // Fused frames trace (traverse and march) in one pass; a two-pass frame's second pass then
  // copies what the first cached.
  const bool fused = fr.value("fused", false);
  // An orbit's frames share a step: they are told apart by number and eye.
  std::string what = concat("step ", u("step"));
  if (job_.orbit > 0) {
    const auto& e = fr["eye"];
    char eye[96];
    std::snprintf(eye, sizeof eye, "%.4g,%.4g,%.4g", e[0].get<double>(), e[1].get<double>(),
                  e[2].get<double>());
    what = concat("frame ", u("frame"), " (", what, ", eye ", eye, ")");
  }
  std::printf(fused ? "  %s: %.1f ms = trace (traversal + march) %.1f + scan %.1f + store %.1f + "
                      "composite %.1f (integration %.1f ms, compositing %.1f ms, slowest rank)\n"
                    : "  %s: %.1f ms = traversal %.1f + scan %.1f + march %.1f + composite %.1f "
                      "(integration %.1f ms, compositing %.1f ms, slowest rank)\n",
              what.c_str(), fr["total_ms"].get<double>(), fr["traversal_ms"].get<double>(),
              fr["scan_ms"].get<double>(), fr["march_ms"].get<double>(),
              fr["composite_ms"].get<double>(), fr["integration_ms"].get<double>(),
              fr["compositing_ms"].get<double>());
  std::printf(
      "    segments/pixel mean %.2f max %.0f; fragments/pixel mean %.2f max %.0f (non-empty "
      "pixels)\n",
      fr["segments_per_pixel_mean_rank0"].get<double>(), fr["segments_per_pixel_max"].get<double>(),
      fr["fragments_per_pixel_mean_rank0"].get<double>(),
      fr["fragments_per_pixel_max"].get<double>());
  std::printf(
      "    lost rays %llu, grazing %llu, entry corrections %llu, step-limit hits %llu, overflow "
      "%llu; "
      "%llu samples, %llu element steps, %llu shell queries, %llu rays ended at the bounding "
      "box, %llu traced again (more segments than cache slots)\n",
      u("lost_rays"), u("grazing_skips"), u("entry_corrections"), u("step_limit_hits"),
      u("fragment_overflow"), u("samples"), u("element_steps"), u("shell_queries"), u("box_exits"),
      u("cache_retraces"));
  if (comm_.size() > 1)
    for (const auto& r : fr["ranks"])
      std::printf(
          "    rank %llu: %llu fragments (%.2f per non-empty pixel), sent %llu bytes (counts %llu "
          "at %u bits, "
          "fragments %llu), composited %llu fragments in %.1f ms\n",
          (unsigned long long)r["rank"].get<uint64_t>(),
          (unsigned long long)r["fragments"].get<uint64_t>(),
          r["fragments_per_nonempty_pixel"].get<double>(),
          (unsigned long long)r["bytes_sent"].get<uint64_t>(),
          (unsigned long long)r["count_bytes_sent"].get<uint64_t>(),
          r["counter_bits"].get<uint32_t>(),
          (unsigned long long)r["fragment_bytes_sent"].get<uint64_t>(),
          (unsigned long long)r["fragments_composited"].get<uint64_t>(),
          r["composite_ms"].get<double>());
}

void StatsReport::finish(uint64_t validationErrors) {
  uint64_t errors = comm::sumOf(comm_, validationErrors);
  json_["validation_errors"] = errors;
  if (comm_.rank() == 0 && job_.stats) {
    printSetup();
    printStartup();
    for (const auto& fr : json_["frames"]) printFrame(fr);
    if (json_.contains("sequence")) printSequenceSummary(json_["sequence"]);
  }
  // Fixed-length lists lose what does not fit (dropped or merged out of order): the image is
  // then approximate, which must be said whether or not --stats was asked for.
  json_["fragment_overflow"] = overflow_;
  if (comm_.rank() == 0 && overflow_ > 0)
    log::warning(
        "fixed-length fragment lists (--k ", job_.lists.fixedK, ") overflowed: ", overflow_,
        " fragments ", job_.lists.mode == comp::ListMode::FixedMerge ? "merged" : "dropped", " in ",
        overflowFrames_, " of ", frames_,
        " frame(s), so the image is approximate; use a larger --k, or --lists two-pass (exact)");
  if (comm_.rank() == 0 && !job_.statsJson.empty()) {
    std::string text = json_.dump(2) + "\n";
    writeBytesAtomically(job_.statsJson,
                         {reinterpret_cast<const uint8_t*>(text.data()), text.size()});
  }
  if (errors) throw Error("the Vulkan validation layer reported ", errors, " error(s)");
}
}  // namespace sm::app
