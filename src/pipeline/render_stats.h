// --stats for render: setup and per-frame statistics, summed or maxed over ranks, printed as a
// table on rank 0 and optionally written as JSON.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "comm/reductions.h"
#include "prep/prepared_rank.h"
#include "render/gpu_scene.h"
#include "render/render_settings.h"
#include "render/renderer.h"
#include "vk/context.h"

namespace sm::app {

struct RenderJob;

// Per-pixel counts summarised: mean over non-empty pixels, maximum, non-empty pixels.
struct PixelCountSummary {
  double meanNonEmpty = 0;
  uint32_t max = 0;
  uint64_t nonEmpty = 0, total = 0;
};
PixelCountSummary summarise(const std::vector<uint32_t>& counts);

class StatsReport {
 public:
  StatsReport(const RenderJob& job, comm::Communicator& comm);
  void setSetup(double loadSeconds, double prepSeconds, bool fromCache,
                const prep::PreparedRank& rank, const render::GpuScene& gpu,
                const std::string& device, const std::string& tracer,
                const render::RenderSettings& s);
  // Collective, after setSetup. Host memory per rank: resident at start, the peak once the mesh
  // was loaded and once prepared (before the device) and now (after setup: the driver included).
  void setHostMemory(uint64_t residentAtStart, uint64_t peakAfterLoad, uint64_t peakAfterPrepare);
  void setUpload(double seconds);        // the scene's buffers and acceleration structures
  void setFrameMemory(const char* key);  // resident bytes now, per rank (collective)
  // Collective when statistics are asked for (gathers every rank's compositing statistics).
  void addFrame(uint64_t step, const scene::Camera& camera, const render::FrameResult& frame,
                const render::Renderer& renderer, comp::DeepCompositor& compositor);
  // What the first frame cost before and while rendering: the context, each pipeline's creation
  // (from the shader cache or compiled), the first frame's wall and device time. Collective.
  void setStartup(const vk::Context& ctx, double firstFrameMs, double firstFrameDeviceMs);
  // The step sequence's summary (SequenceStats), printed after the frames and kept as "sequence".
  void setSequence(nlohmann::json summary) { json_["sequence"] = std::move(summary); }
  // Prints (rank 0) and writes JSON; throws when validation reported errors.
  void finish(uint64_t validationErrors);

 private:
  const RenderJob& job_;
  comm::Communicator& comm_;
  nlohmann::json json_;
  uint64_t preparedBytes_ = 0;  // this rank's, from setSetup (which setHostMemory follows)
  // Counted with or without --stats: an overflow must be said either way.
  uint64_t overflow_ = 0, overflowFrames_ = 0, frames_ = 0;
  bool wanted() const;
  // Per-rank values as the paper's table reports them: min, max and average over ranks
  // (collective).
  nlohmann::json spread(double v) const;
  void printSetup() const;
  void printStartup() const;
  void printFrame(const nlohmann::json& fr) const;
};

}  // namespace sm::app
