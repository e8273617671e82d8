#include "compositor/tools/replay.h"

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>

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

// Step 2's bytes from source s to every destination at each counter width it may be sent with
// (known only once every rank's longest list is; never below what s's own longest list needs): a
// header and the payload count_codec.h chooses, as DeepExchange::transferCounts sends them.
struct CountBytes {
  std::vector<uint32_t> position;  // of each pixel, computed once
  std::vector<uint32_t> byPosition, words;
  std::vector<std::vector<uint64_t>> sent, received;  // [width][rank]

  CountBytes(const PixelRanges& ranges)
      : position(ranges.pixels()),
        byPosition(ranges.pixels()),
        sent(std::size(kWidths), std::vector<uint64_t>(size_t(ranges.ranks()), 0)),
        received(sent) {
    for (uint64_t p = 0; p < ranges.pixels(); ++p) position[p] = uint32_t(ranges.positionOf(p));
  }

  void add(const PixelRanges& ranges, int s, std::span<const uint32_t> counts, uint32_t longest,
           uint32_t forcedBits) {
    for (uint64_t p = 0; p < counts.size(); ++p) byPosition[position[p]] = counts[p];
    for (size_t w = 0; w < std::size(kWidths); ++w) {
      if (forcedBits != 0 ? forcedBits != kWidths[w] : kWidths[w] < counterBits(longest)) continue;
      const CountExchange plan = planCountExchange(ranges, s, kWidths[w]);
      for (int d = 0; d < ranges.ranks(); ++d) {
        if (d == s) continue;
        packCounterWords({byPosition.data() + ranges.begin(d), ranges.count(d)}, kWidths[w], words);
        const uint64_t bytes =
            kPayloadHeaderBytes + choosePayload(words, plan.transfer.sendBytes[size_t(d)]).bytes;
        sent[w][size_t(s)] += bytes;
        received[w][size_t(d)] += bytes;
      }
    }
  }
};

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
  std::optional<CountBytes> countBytes;
  if (ranks > 1) countBytes.emplace(ranges);
  for (int s = 0; s < ranks; ++s) {
    counts.assign(pixels, 0);
    source(s, counts);
    if (counts.size() != pixels)
      throw std::invalid_argument("replay: rank " + std::to_string(s) + " has " +
                                  std::to_string(counts.size()) + " counts for " +
                                  std::to_string(pixels) + " pixels");
    ReplayRank& rs = out.ranks[size_t(s)];
    for (uint32_t c : counts) {
      rs.fragments += c;
      rs.nonEmptyPixels += c > 0;
      rs.longestList = std::max(rs.longestList, c);
    }
    longest = std::max<uint64_t>(longest, rs.longestList);
    if (countBytes) countBytes->add(ranges, s, counts, rs.longestList, forcedBits);
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
  for (int r = 0; countBytes && r < ranks; ++r) {
    out.ranks[size_t(r)].countBytesSent = countBytes->sent[w][size_t(r)];
    out.ranks[size_t(r)].countBytesReceived = countBytes->received[w][size_t(r)];
  }
  return out;
}

}  // namespace sm::comp
