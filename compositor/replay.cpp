#include "compositor/replay.h"

#include <algorithm>

#include "compositor/count_codec.h"
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

namespace {

constexpr uint32_t kWidths[] = {2, 4, 8, 32};

// Step 2's bytes from source s to every destination at every counter width (the width is known
// only once every rank's longest list is): a header and the payload count_codec.h chooses, as
// DeepExchange::transferCounts sends them.
void addCountBytes(const PixelRanges& ranges, int s, std::span<const uint32_t> counts,
                   uint32_t forcedBits, std::vector<std::vector<uint64_t>>& sent,
                   std::vector<std::vector<uint64_t>>& received) {
  const int R = ranges.ranks();
  std::vector<uint32_t> byPosition(counts.size()), code;
  for (uint64_t p = 0; p < counts.size(); ++p) byPosition[ranges.positionOf(p)] = counts[p];
  for (size_t w = 0; w < std::size(kWidths); ++w) {
    if (forcedBits != 0 && forcedBits != kWidths[w]) continue;
    const CountExchange plan = planCountExchange(ranges, s, kWidths[w]);
    for (int d = 0; d < R; ++d) {
      if (d == s) continue;
      const std::span<const uint32_t> share(byPosition.data() + ranges.begin(d), ranges.count(d));
      code.clear();
      appendZeroRuns(packCounterWords(share, kWidths[w]), code);
      const uint64_t bytes =
          8 + choosePayload(plan.transfer.sendBytes[size_t(d)], code.size()).bytes;
      sent[w][size_t(s)] += bytes;
      received[w][size_t(d)] += bytes;
    }
  }
}

}  // namespace

ReplayResult replayExchange(uint64_t pixels, int ranks, Encoding encoding, uint32_t forcedBits,
                            PixelOwnership ownership, const CountSource& source) {
  const PixelRanges ranges(pixels, ranks, ownership);
  ReplayResult out;
  out.pixels = pixels;
  out.fragmentBytes = fragmentBytes(encoding);
  out.ranks.resize(size_t(ranks));
  std::vector<uint32_t> counts;
  uint64_t longest = 0;
  std::vector<std::vector<uint64_t>> countSent(std::size(kWidths),
                                               std::vector<uint64_t>(size_t(ranks), 0));
  std::vector<std::vector<uint64_t>> countReceived = countSent;
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
    if (ranks > 1) addCountBytes(ranges, s, counts, forcedBits, countSent, countReceived);
    std::vector<uint64_t> to = fragmentsPerDestination(ranges, counts);
    for (int d = 0; d < ranks; ++d) {
      out.ranks[size_t(d)].fragmentsComposited += to[size_t(d)];
      if (d == s) continue;
      rs.fragmentBytesSent += to[size_t(d)] * out.fragmentBytes;
      out.ranks[size_t(d)].fragmentBytesReceived += to[size_t(d)] * out.fragmentBytes;
    }
  }
  // The width is chosen from every rank's longest list.
  out.counterBits = chooseCounterBits(longest, forcedBits);
  const size_t w = size_t(std::find(std::begin(kWidths), std::end(kWidths), out.counterBits) -
                          std::begin(kWidths));
  for (int r = 0; r < ranks; ++r) {
    out.ranks[size_t(r)].countBytesSent = countSent[w][size_t(r)];
    out.ranks[size_t(r)].countBytesReceived = countReceived[w][size_t(r)];
  }
  return out;
}

}  // namespace sm::comp
