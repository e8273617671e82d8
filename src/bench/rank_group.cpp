#include "bench/rank_group.h"

#include <algorithm>
#include <mutex>

#include "bench/bench_common.h"
#include "comm/local_communicator.h"
#include "common/error.h"
#include "common/timer.h"
#include "partition/partition.h"
#include "prep/prepare.h"
#include "render/gpu_scene.h"
#include "render/renderer.h"
#include "session/rank_session.h"
#include "vk/context.h"

namespace sm::app::bench {

struct RankGroup::Shares {
  std::vector<prep::PreparedRank> ranks;
  std::vector<std::vector<float>> scalars;  // per rank, in its prepared vertex order
};

RankGroup::RankGroup(const mesh::UnstructuredMesh& input, const std::string& field, int ranks,
                     int clusters, const std::string& device, Dealing dealing)
    : shares_(std::make_unique<Shares>()), device_(device) {
  if (ranks < 1 || clusters < ranks)
    throw Error("--ranks ", ranks, " and --clusters ", clusters, ": need 1 <= ranks <= clusters");
  const mesh::Field* f = input.findField(field);
  if (!f) throw Error("no point field '", field, "' in ", input.source);
  mesh::UnstructuredMesh whole = input;
  partition::assignMetisClusters(whole, clusters);
  const prep::GlobalFrame frame = prep::makeGlobalFrame(whole.bounds());
  for (int r = 0; r < ranks; ++r) {
    // Round-robin: neighbouring clusters land on different ranks, so every rank's share is
    // scattered through the volume and interlocks with the others'.
    std::vector<int> mine;
    for (int c = 0; c < clusters; ++c)
      if (dealing == Dealing::RoundRobin ? c % ranks == r : r == 0) mine.push_back(c);
    partition::ExtractedClusters e = partition::extractClustersWithPointMap(whole, mine);
    std::vector<float> values(e.originalPoint.size());
    for (size_t i = 0; i < values.size(); ++i) values[i] = f->steps[0][e.originalPoint[i]];
    prep::PrepResult p = prep::prepareRank(e.mesh, frame, prep::PrepOptions{true});
    shares_->scalars.push_back(prep::gatherScalars(p.rank, values));
    shares_->ranks.push_back(std::move(p.rank));
  }
}

RankGroup::~RankGroup() = default;

int RankGroup::ranks() const {
  return int(shares_->ranks.size());
}

GroupFrame RankGroup::render(const render::RenderSettings& settings,
                             const comp::CompositorOptions& lists, int runs) {
  const int n = ranks();
  std::vector<std::vector<double>> ms(n);
  std::vector<uint64_t> fragments(n), overflow(n), lost(n);
  GroupFrame out;
  comm::runLocalRanks(n, [&](comm::Communicator& comm) {
    const int r = comm.rank();
    vk::ContextOptions o;
    o.device = device_;
    session::RankSession session(o, &comm, session::SessionOptions{lists});
    const vk::Context& ctx = session.context();
    // Copied: the group renders its ranks again for other list modes.
    render::GpuScene& scene = session.setScene(shares_->ranks[r], shares_->ranks[r].positions);
    if (!shares_->scalars[r].empty()) scene.setScalars(shares_->scalars[r]);
    session.renderer(settings.width, settings.height);  // lists allocated before the clock runs
    render::FrameResult frame;
    for (int i = 0; i <= runs; ++i) {  // frame 0 is cold (pipelines compile on first dispatch)
      comm.barrier();
      Timer t;
      frame = session.render(settings, std::move(frame.pixels));
      if (i > 0) ms[r].push_back(t.ms());
    }
    fragments[r] = frame.counters.fragments;
    overflow[r] = frame.counters.overflow;
    lost[r] = frame.counters.lostRays;
    if (ctx.validationErrors())
      throw Error("rank ", r, ": the Vulkan validation layer reported ", ctx.validationErrors(),
                  " error(s)");
    if (r == 0) {
      out.image = scene::Image(settings.width, settings.height);
      out.image.pixels = std::move(frame.pixels);
    }
  });
  std::vector<double> slowest(size_t(runs), 0.0);
  for (int r = 0; r < n; ++r)
    for (int i = 0; i < runs; ++i) slowest[i] = std::max(slowest[i], ms[r][i]);
  out.ms = median(slowest);
  uint64_t covered = 0, total = 0;
  for (const auto& p : out.image.pixels) covered += p.a > 0 ? 1 : 0;
  for (int r = 0; r < n; ++r) {
    total += fragments[r];
    out.overflow += overflow[r];
    out.lostRays += lost[r];
  }
  out.fragmentsPerPixel = covered ? double(total) / double(covered) : 0.0;
  return out;
}

}  // namespace sm::app::bench
