// The run mode: deep compositing of synthetic lists on the ranks of MPI_COMM_WORLD, for each
// image size, fragment encoding and counter width that holds the longest list.
#include <algorithm>
#include <cstdio>
#include <fstream>

#include "bench.h"
#include "comm/mpi/mpi_communicator.h"
#include "comm/mpi/mpi_session.h"
#include "compositor/host_lists.h"
#include "compositor/tools/count_dump.h"
#include "synthetic.h"
#include "vk/context.h"

namespace sm::comp::bench {
namespace {

struct FrameTimes {
  std::vector<double> total, prepare, counts, fragments, composite, gather;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// The slowest rank's time (a frame is done when the last rank is).
double slowest(comm::Communicator& comm, double ms) {
  return double(comm.allreduceMax(uint64_t(ms * 1000.0))) / 1000.0;
}

nlohmann::json measure(comm::Communicator& comm, const vk::Context& ctx, const HostLists& lists,
                       int size, const CompositorOptions& o, int frames) {
  DeepCompositor compositor(ctx, &comm, size, size, o);
  ListWriter(compositor).write(lists);
  // One image for every frame, as a renderer's frame loop keeps it: a fresh 64 MiB image per
  // frame (2048²) cost more in page faults than compositing it on a GPU.
  std::vector<glm::vec4> image;
  compositor.composite(CompositeMethod::Deep, image);  // warm-up: pipelines compile, buffers grow
  FrameTimes t;
  for (int f = 0; f < frames; ++f) {
    comm.barrier();
    compositor.composite(CompositeMethod::Deep, image);
    const CompositeStats& s = compositor.stats();
    t.total.push_back(slowest(comm, s.milliseconds));
    t.prepare.push_back(slowest(comm, s.timings.prepare));
    t.counts.push_back(slowest(comm, s.timings.countExchange));
    t.fragments.push_back(slowest(comm, s.timings.fragmentExchange));
    t.composite.push_back(slowest(comm, s.timings.composite));
    t.gather.push_back(slowest(comm, s.timings.gather));
  }
  const CompositeStats& s = compositor.stats();
  const uint64_t fragments = comm.allreduceSum(s.fragments);
  const uint64_t busiest = comm.allreduceMax(s.fragmentsComposited);
  const double balanced = double(fragments) / comm.size();
  return {{"ranks", comm.size()},
          {"size", size},
          {"encoding", o.encoding == Encoding::Float ? "float" : "rgba8"},
          {"ownership", ownershipName(o.ownership)},
          {"counterBits", s.counterBits},
          {"fragments", fragments},
          {"countBytes", comm.allreduceSum(s.countBytesSent)},
          {"fragmentBytes", comm.allreduceSum(s.fragmentBytesSent)},
          {"ms", median(t.total)},
          {"prepareMs", median(t.prepare)},
          {"countExchangeMs", median(t.counts)},
          {"fragmentExchangeMs", median(t.fragments)},
          {"compositeMs", median(t.composite)},
          {"gatherMs", median(t.gather)},
          {"compositeImbalance", balanced > 0 ? double(busiest) / balanced : 0.0}};
}

void dumpCounts(DeepCompositor& compositor, const std::string& path, int size) {
  if (dumpFrameCounts(compositor, path) > 0)
    std::printf("wrote per-rank fragment counts of %dx%d to %s\n", size, size, path.c_str());
}

void runAll(comm::MpiCommunicator& comm, const RunOptions& o) {
  vk::ContextOptions co;
  co.rayTracing = false;
  vk::Context ctx(co);
  nlohmann::json rows = nlohmann::json::array();
  const int R = comm.size();
  std::vector<PixelOwnership> ownerships;
  for (const std::string& name : o.ownerships) ownerships.push_back(parseOwnership(name));
  for (int size : o.sizes) {
    SyntheticScene scene(size, size, R, o.depthBlocks);
    HostLists lists = scene.lists(comm.rank());
    uint32_t mine = 0;
    for (uint32_t c : lists.counts) mine = std::max(mine, c);
    const uint64_t longest = comm.allreduceMax(mine);
    for (Encoding e : {Encoding::Float, Encoding::Rgba8}) {
      for (uint32_t bits : {2u, 4u, 8u, 32u}) {
        if (R > 1 && bits < 32 && longest >= (uint64_t(1) << bits)) continue;  // cannot hold
        if (R == 1 && bits != 32) continue;  // no exchange: one row per encoding
        for (PixelOwnership own : ownerships) {
          if (R == 1 && own != ownerships.front()) continue;  // one rank owns every pixel
          CompositorOptions co2;
          co2.encoding = e;
          co2.counterBits = R > 1 ? bits : 0;
          co2.ownership = own;
          rows.push_back(measure(comm, ctx, lists, size, co2, o.frames));
        }
      }
    }
    if (!o.dumpCounts.empty() && size == o.sizes.back()) {
      DeepCompositor compositor(ctx, &comm, size, size, {});
      ListWriter(compositor).write(lists);
      compositor.composite();
      dumpCounts(compositor, o.dumpCounts, size);
    }
  }
  if (comm.rank() != 0) return;
  printRunTable(rows);
  if (!o.json.empty()) {
    std::ofstream(o.json) << rows.dump(1) << "\n";
    std::printf("wrote %s\n", o.json.c_str());
  }
}

}  // namespace

void printRunTable(const nlohmann::json& rows) {
  std::printf("%5s %5s %5s %4s %11s %10s %10s %11s %9s %8s | %7s %7s %7s %7s %7s %6s\n", "ranks",
              "size", "frag", "bits", "ownership", "fragments", "count B", "fragment B", "MB/frame",
              "ms", "prep", "counts", "frags", "comp", "gather", "imbal");
  for (const auto& r : rows) {
    const double mb = (double(r["countBytes"]) + double(r["fragmentBytes"])) / 1e6;
    const uint32_t bits = r["counterBits"];
    std::printf(
        "%5d %5d %5s %4s %11s %10llu %10llu %11llu %9.2f %8.1f | %7.1f %7.1f %7.1f %7.1f %7.1f "
        "%6.2f\n",
        int(r["ranks"]), int(r["size"]), std::string(r["encoding"]).c_str(),
        bits ? std::to_string(bits).c_str() : "-",
        int(r["ranks"]) > 1 ? std::string(r["ownership"]).c_str() : "-",
        (unsigned long long)r["fragments"], (unsigned long long)r["countBytes"],
        (unsigned long long)r["fragmentBytes"], mb, double(r["ms"]), double(r["prepareMs"]),
        double(r["countExchangeMs"]), double(r["fragmentExchangeMs"]), double(r["compositeMs"]),
        double(r["gatherMs"]), double(r["compositeImbalance"]));
  }
}

int runBenchmark(const RunOptions& o) {
  comm::MpiSession session;
  comm::MpiCommunicator comm;
  comm::runOrAbort(comm, [&] { runAll(comm, o); });
  return 0;
}

}  // namespace sm::comp::bench
