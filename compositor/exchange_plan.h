// Host-side arithmetic of the exchange (steps 2 and 3 of the paper's deep compositing): which rank
// owns which pixels, how many bits a counter takes, and how many bytes go where. Shared by the
// compositor and by the replay that predicts traffic for rank counts this machine cannot run.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace sm::comp {

// Rank r composites pixels [begin(r), begin(r + 1)), begin(r) = floor(r P / R): contiguous ranges,
// so each destination's share of a rank's pixel-ordered send buffer is contiguous too.
class PixelRanges {
 public:
  PixelRanges(uint64_t pixels, int ranks);
  uint64_t pixels() const { return pixels_; }
  int ranks() const { return ranks_; }
  uint64_t begin(int r) const { return uint64_t(r) * pixels_ / uint64_t(ranks_); }
  uint64_t end(int r) const { return begin(r + 1); }
  uint64_t count(int r) const { return end(r) - begin(r); }
  int owner(uint64_t pixel) const;

 private:
  uint64_t pixels_;
  int ranks_;
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

// Step 3: sendBegin[d] is the first fragment (in the pixel-ordered send buffer) for rank d and
// recvBegin[s] the first received fragment from rank s; both have ranks + 1 entries, the last the
// total.
Transfer planFragmentExchange(std::span<const uint64_t> sendBegin,
                              std::span<const uint64_t> recvBegin, uint32_t fragmentBytes);

// Fragments rank-local per-pixel `counts` send to each destination (ranks entries).
std::vector<uint64_t> fragmentsPerDestination(const PixelRanges& ranges,
                                              std::span<const uint32_t> counts);

}  // namespace sm::comp
