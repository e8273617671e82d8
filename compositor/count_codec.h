// The count exchange's payload (step 2): each destination's counters packed into 32-bit words as
// encode_counts.comp packs them, sent as they are or, where it is smaller, as runs of zero words
// (IceT run-length codes the inactive pixels of its images for the same reason). A rank whose data
// covers few of a destination's pixels has mostly zero words for it: at the paper's 552 ranks the
// packed counters were six times the fragment traffic of a real frame (docs/BENCHMARKS.md).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace sm::comp {

// Counters (one per position of a destination's range, in position order) packed `bits` each,
// 32 / bits per word from the low bits up: encode_counts.comp's layout (bits < 32), or the counts
// themselves (bits == 32), into `words` (resized; no allocation once it is large enough).
void packCounterWords(std::span<const uint32_t> counters, uint32_t bits,
                      std::vector<uint32_t>& words);

// Appends the zero-run code of `words` to `out`: records of (z, n, n literal words) meaning z zero
// words then the n literals, until every word is described. A single zero between non-zero words
// stays a literal (a new record would cost two words), as does a single zero at the end.
void appendZeroRuns(std::span<const uint32_t> words, std::vector<uint32_t>& out);
// How many words appendZeroRuns would append.
uint64_t zeroRunWords(std::span<const uint32_t> words);

// Expands a zero-run code into exactly words.size() words; throws CommError when the code does not
// describe exactly that many (a transfer that went wrong, not a user error).
void expandZeroRuns(std::span<const uint32_t> code, std::span<uint32_t> words);

// What one destination's share of packed `words` costs to send: denseBytes (the bytes that hold
// counters), or its zero-run code's when that is smaller. zeroRuns says which was chosen. The
// compositor sends what this chooses and the replay counts it.
struct CountPayload {
  uint64_t bytes = 0;
  bool zeroRuns = false;
};
CountPayload choosePayload(std::span<const uint32_t> words, uint64_t denseBytes);

// The header each pair of ranks exchanges before the payload: its size, and the top bit set for a
// zero-run code.
constexpr uint64_t kPayloadHeaderBytes = sizeof(uint64_t);
constexpr uint64_t kZeroRunFlag = uint64_t(1) << 63;
inline uint64_t payloadHeader(const CountPayload& p) {
  return p.bytes | (p.zeroRuns ? kZeroRunFlag : 0);
}

}  // namespace sm::comp
