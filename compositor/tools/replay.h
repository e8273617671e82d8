// Replays the exchange (steps 1-3) from per-rank, per-pixel fragment counts without MPI or a GPU:
// the same ownership, counter encoding and byte accounting as DeepExchange, for rank counts this
// machine cannot run (the paper's 72 and 552). Ranks' counts are streamed one at a time.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "compositor/deep_compositor.h"

namespace sm::comp {

struct ReplayRank {
  uint64_t fragments = 0;  // generated on this rank
  uint64_t nonEmptyPixels = 0;
  uint32_t longestList = 0;
  uint64_t countBytesSent = 0, fragmentBytesSent = 0;          // to other ranks, as CompositeStats
  uint64_t countBytesReceived = 0, fragmentBytesReceived = 0;  // from other ranks
  uint64_t fragmentsComposited = 0;  // of the pixels this rank owns, from all ranks
};

struct ReplayResult {
  uint64_t pixels = 0;
  uint32_t counterBits = 0;
  uint32_t fragmentBytes = 0;
  std::vector<ReplayRank> ranks;
  // max / mean over ranks (1 = perfect balance; 0 when every value is 0).
  double imbalance(uint64_t ReplayRank::*field) const;
  uint64_t maximum(uint64_t ReplayRank::*field) const;
  double mean(uint64_t ReplayRank::*field) const;
};

// Fills `counts` (pixels entries) with rank r's per-pixel fragment counts.
using CountSource = std::function<void(int rank, std::vector<uint32_t>& counts)>;

ReplayResult replayExchange(uint64_t pixels, int ranks, Encoding encoding, uint32_t forcedBits,
                            PixelOwnership ownership, const CountSource& source);

}  // namespace sm::comp
