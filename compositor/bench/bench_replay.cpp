// The replay mode: the exchange's byte accounting and load balance for rank counts this machine
// cannot run (the paper's 72 and 552), from the synthetic scene or a count dump.
#include <cstdio>
#include <fstream>

#include "bench.h"
#include "compositor/tools/count_dump.h"
#include "compositor/tools/replay.h"
#include "synthetic.h"

namespace sm::comp::bench {
namespace {

struct Spread {
  double min = 0, mean = 0, max = 0;
};

Spread spread(const ReplayResult& r, uint64_t ReplayRank::*field, double scale = 1.0) {
  Spread s{1e300, r.mean(field) * scale, double(r.maximum(field)) * scale};
  for (const ReplayRank& k : r.ranks) s.min = std::min(s.min, double(k.*field) * scale);
  return s;
}

// r: interleaved ownership (the compositor's default); ranges: the same counts with the paper's
// contiguous pixel ranges, for the compositing balance of both.
nlohmann::json row(const ReplayResult& r, const ReplayResult& ranges, int width, int height,
                   const std::string& source) {
  // The same fragments in rgba8 take 8 bytes instead of 20.
  const double toRgba8 = double(fragmentBytes(Encoding::Rgba8)) / r.fragmentBytes;
  auto json = [](Spread s) {
    return nlohmann::json{{"min", s.min}, {"mean", s.mean}, {"max", s.max}};
  };
  return {{"ranks", r.ranks.size()},
          {"width", width},
          {"height", height},
          {"source", source},
          {"counterBits", r.counterBits},
          {"fragments", r.mean(&ReplayRank::fragments) * double(r.ranks.size())},
          {"countBytesSent", json(spread(r, &ReplayRank::countBytesSent))},
          {"fragmentBytesSentFloat", json(spread(r, &ReplayRank::fragmentBytesSent))},
          {"fragmentBytesSentRgba8", json(spread(r, &ReplayRank::fragmentBytesSent, toRgba8))},
          {"fragmentBytesReceivedFloat", json(spread(r, &ReplayRank::fragmentBytesReceived))},
          {"renderImbalance", r.imbalance(&ReplayRank::fragments)},
          {"compositeImbalance", r.imbalance(&ReplayRank::fragmentsComposited)},
          {"compositeImbalanceRanges", ranges.imbalance(&ReplayRank::fragmentsComposited)}};
}

void printTable(const nlohmann::json& rows) {
  std::printf("%6s %9s %4s %10s | %-29s | %-29s | %-29s | %6s %6s %6s\n", "ranks", "image", "bits",
              "fragments", "count kB sent per rank", "float fragment kB sent/rank",
              "rgba8 fragment kB sent/rank", "render", "comp", "comp");
  std::printf("%6s %9s %4s %10s |", "", "", "", "");
  for (int i = 0; i < 3; ++i) std::printf(" %9s %9s %9s |", "min", "mean", "max");
  std::printf(" %6s %6s %6s\n", "imbal", "imbal", "ranges");
  auto k = [](const nlohmann::json& s, const char* f) { return double(s[f]) / 1e3; };
  for (const auto& r : rows) {
    std::string image = std::to_string(int(r["width"])) + "x" + std::to_string(int(r["height"]));
    std::printf("%6d %9s %4d %10.0f |", int(r["ranks"]), image.c_str(), int(r["counterBits"]),
                double(r["fragments"]));
    for (const char* f : {"countBytesSent", "fragmentBytesSentFloat", "fragmentBytesSentRgba8"})
      std::printf(" %9.1f %9.1f %9.1f |", k(r[f], "min"), k(r[f], "mean"), k(r[f], "max"));
    std::printf(" %6.2f %6.2f %6.2f\n", double(r["renderImbalance"]),
                double(r["compositeImbalance"]), double(r["compositeImbalanceRanges"]));
  }
}

}  // namespace

int replayBenchmark(const ReplayOptions& o) {
  nlohmann::json rows = nlohmann::json::array();
  if (!o.dump.empty()) {
    CountDumpReader reader(o.dump);
    auto replay = [&](PixelOwnership own) {
      return replayExchange(
          uint64_t(reader.width()) * reader.height(), int(reader.ranks()), Encoding::Float,
          o.counterBits, own,
          [&](int rank, std::vector<uint32_t>& c) { reader.read(uint32_t(rank), c); });
    };
    rows.push_back(row(replay(PixelOwnership::Interleaved), replay(PixelOwnership::Ranges),
                       int(reader.width()), int(reader.height()), o.dump));
  } else {
    for (int ranks : o.ranks) {
      SyntheticScene scene(o.width, o.height, ranks, o.depthBlocks);
      auto replay = [&](PixelOwnership own) {
        return replayExchange(uint64_t(o.width) * o.height, ranks, Encoding::Float, o.counterBits,
                              own,
                              [&](int rank, std::vector<uint32_t>& c) { scene.counts(rank, c); });
      };
      rows.push_back(row(replay(PixelOwnership::Interleaved), replay(PixelOwnership::Ranges),
                         o.width, o.height,
                         "synthetic, " + std::to_string(scene.blocks()) + "^3 blocks"));
    }
  }
  printTable(rows);
  if (!o.json.empty()) {
    std::ofstream(o.json) << rows.dump(1) << "\n";
    std::printf("wrote %s\n", o.json.c_str());
  }
  return 0;
}

}  // namespace sm::comp::bench
