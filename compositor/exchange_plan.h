// Host-side arithmetic of the exchange (steps 2 and 3 of the paper's deep compositing): which rank
// owns which pixels, how many bits a counter takes, and how many bytes go where. Shared by the
// compositor and by the replay that predicts traffic for rank counts this machine cannot run.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "exchange_types.h"

namespace sm::comp {

// Which rank composites which pixels (exchange_types.h). Ranges: contiguous blocks of
// the image, as the paper has it; a view whose data covers part of the image leaves the ranks
// owning the rest with nothing to composite. Interleaved: rank r owns every R-th pixel, so every
// rank's share of the covered pixels is about 1/R whatever the view.
enum class PixelOwnership : uint32_t {
  Interleaved = DC_OWNERSHIP_INTERLEAVED,
  Ranges = DC_OWNERSHIP_RANGES,
};
const char* ownershipName(PixelOwnership o);
PixelOwnership parseOwnership(const std::string& name);  // "interleaved" or "ranges"; throws

// Rank r composites exchange positions [begin(r), end(r)): contiguous, so each destination's share
// of a rank's position-ordered send buffer is contiguous too. Position q stands for pixel
// pixelAt(q): q itself with Ranges (begin(r) = floor(r P / R)); with Interleaved, the pixels
// p = r (mod R) in order (begin(r) = r floor(P / R) + min(r, P mod R)).
// (m, l - 1) of dcDivide for 2 <= divisor < 2^32.
DcDivisor dcDivisionMagic(uint32_t divisor);

class PixelRanges {
 public:
  PixelRanges(uint64_t pixels, int ranks, PixelOwnership ownership);
  uint64_t pixels() const { return pixels_; }
  int ranks() const { return ranks_; }
  PixelOwnership ownership() const { return ownership_; }
  uint64_t begin(int r) const;
  uint64_t end(int r) const { return begin(r + 1); }
  uint64_t count(int r) const { return end(r) - begin(r); }
  int owner(uint64_t position) const;
  uint64_t pixelAt(uint64_t position) const;
  uint64_t positionOf(uint64_t pixel) const;
  int ownerOfPixel(uint64_t pixel) const;
  uint32_t base() const { return uint32_t(pixels_ / uint64_t(ranks_)); }   // floor(P / R)
  uint32_t extra() const { return uint32_t(pixels_ % uint64_t(ranks_)); }  // P mod R
  DcDivisor byRanks() const;                                               // for dcDivide; R >= 2

 private:
  uint64_t pixels_;
  int ranks_;
  PixelOwnership ownership_;
};

// Bits per counter in the count exchange: the smallest of 2, 4, 8, 32 that holds the longest list
// of any rank (lengths 0-3, 4-15, 16-255, longer).
uint32_t counterBits(uint64_t maxListLength);
// counterBits, or `forced` when it is non-zero (it must be 2, 4, 8 or 32 and hold the longest
// list).
uint32_t chooseCounterBits(uint64_t maxListLength, uint32_t forced);
inline uint64_t encodedWords(uint64_t counters, uint32_t bits) {
  return (counters * bits + 31) / 32;
}
inline uint64_t encodedBytes(uint64_t counters, uint32_t bits) {
  return (counters * bits + 7) / 8;
}

// Byte sizes and offsets of one alltoallv, as the Communicator takes them.
struct Transfer {
  std::vector<uint64_t> sendBytes, sendOffsets, recvBytes, recvOffsets;
  uint64_t sendTotal() const;  // including the share a rank keeps
  uint64_t recvTotal() const;
  uint64_t sentToOthers(int self) const;
};

// Step 2 on `rank`. Counts for destination d are packed into whole 32-bit words starting at word
// sendWordBegin[d] (only the bytes that hold counters are sent); the counters received from source
// s start at word s * wordsPerSource.
struct CountExchange {
  uint32_t bits = 32;
  std::vector<uint64_t> sendWordBegin;  // ranks + 1 entries
  uint64_t wordsPerSource = 0;
  Transfer transfer;
};
CountExchange planCountExchange(const PixelRanges& ranges, int rank, uint32_t bits);

// Step 3: sendBegin[d] is the first fragment (in the position-ordered send buffer) for rank d and
// recvBegin[s] the first received fragment from rank s; both have ranks + 1 entries, the last the
// total.
Transfer planFragmentExchange(std::span<const uint64_t> sendBegin,
                              std::span<const uint64_t> recvBegin, uint32_t fragmentBytes);

// Fragments rank-local per-pixel `counts` (in image order) send to each destination (ranks
// entries).
std::vector<uint64_t> fragmentsPerDestination(const PixelRanges& ranges,
                                              std::span<const uint32_t> counts);

}  // namespace sm::comp
