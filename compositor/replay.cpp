#include "compositor/replay.h"

#include <algorithm>

#include "compositor/exchange_plan.h"

namespace sm::comp {

double ReplayResult::imbalance(uint64_t ReplayRank::*field) const {
  const double m = mean(field);
  return m > 0.0 ? double(maximum(field)) / m : 0.0;
}

uint64_t ReplayResult::maximum(uint64_t ReplayRank::*field) const {
  uint64_t m = 0;
  for (const ReplayRank& r : ranks) m = std::max(m, r.*field);
  return m;
}

double ReplayResult::mean(uint64_t ReplayRank::*field) const {
  if (ranks.empty()) return 0.0;
  double s = 0.0;
  for (const ReplayRank& r : ranks) s += double(r.*field);
  return s / double(ranks.size());
}

ReplayResult replayExchange(uint64_t pixels, int ranks, Encoding encoding, uint32_t forcedBits,
                            PixelOwnership ownership, const CountSource& source) {
  const PixelRanges ranges(pixels, ranks, ownership);
  ReplayResult out;
  out.pixels = pixels;
  out.fragmentBytes = fragmentBytes(encoding);
  out.ranks.resize(size_t(ranks));
  std::vector<uint32_t> counts;
  uint64_t longest = 0;
  for (int s = 0; s < ranks; ++s) {
    counts.assign(pixels, 0);
    source(s, counts);
    ReplayRank& rs = out.ranks[size_t(s)];
    for (uint32_t c : counts) {
      rs.fragments += c;
      rs.nonEmptyPixels += c > 0;
      rs.longestList = std::max(rs.longestList, c);
    }
    longest = std::max<uint64_t>(longest, rs.longestList);
    std::vector<uint64_t> to = fragmentsPerDestination(ranges, counts);
    for (int d = 0; d < ranks; ++d) {
      out.ranks[size_t(d)].fragmentsComposited += to[size_t(d)];
      if (d == s) continue;
      rs.fragmentBytesSent += to[size_t(d)] * out.fragmentBytes;
      out.ranks[size_t(d)].fragmentBytesReceived += to[size_t(d)] * out.fragmentBytes;
    }
  }
  // Counter sizes depend only on the width (chosen from every rank's longest list) and ranges.
  out.counterBits = chooseCounterBits(longest, forcedBits);
  for (int r = 0; r < ranks; ++r) {
    CountExchange c = planCountExchange(ranges, r, out.counterBits);
    out.ranks[size_t(r)].countBytesSent = c.transfer.sentToOthers(r);
    out.ranks[size_t(r)].countBytesReceived =
        c.transfer.recvTotal() - c.transfer.recvBytes[size_t(r)];
  }
  return out;
}

}  // namespace sm::comp
