#include "compositor/exchange_plan.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace sm::comp {

const char* ownershipName(PixelOwnership o) {
  return o == PixelOwnership::Interleaved ? "interleaved" : "ranges";
}

PixelOwnership parseOwnership(const std::string& name) {
  if (name == "interleaved") return PixelOwnership::Interleaved;
  if (name == "ranges") return PixelOwnership::Ranges;
  throw std::invalid_argument("pixel ownership '" + name + "' (use interleaved or ranges)");
}

PixelRanges::PixelRanges(uint64_t pixels, int ranks, PixelOwnership ownership)
    : pixels_(pixels), ranks_(ranks), ownership_(ownership) {
  if (ranks < 1) throw std::invalid_argument("pixel ranges need at least one rank");
  // The shaders index positions and pixels with 32 bits.
  if (pixels > 0xFFFFFFFFull)
    throw std::invalid_argument("an image of " + std::to_string(pixels) +
                                " pixels (the compositor takes at most 2^32 - 1)");
}

DcDivisor dcDivisionMagic(uint32_t d) {
  if (d < 2) throw std::invalid_argument("dcDivide needs a divisor of at least 2");
  uint32_t l = 0;
  while ((uint64_t(1) << l) < d) ++l;
  const uint64_t m = (uint64_t(1) << 32) * ((uint64_t(1) << l) - d) / d + 1;
  return {uint32_t(m), l - 1};
}

DcDivisor PixelRanges::byRanks() const {
  return dcDivisionMagic(uint32_t(ranks_));
}

uint64_t PixelRanges::begin(int r) const {
  const uint64_t R = uint64_t(ranks_);
  if (ownership_ == PixelOwnership::Ranges) return uint64_t(r) * pixels_ / R;
  return uint64_t(r) * (pixels_ / R) + std::min<uint64_t>(uint64_t(r), pixels_ % R);
}

int PixelRanges::owner(uint64_t q) const {
  if (q >= pixels_)
    throw std::out_of_range("position " + std::to_string(q) + " outside an image of " +
                            std::to_string(pixels_));
  const uint64_t R = uint64_t(ranks_);
  // begin(d) <= q  <=>  d <= ((q + 1) R - 1) / P  (integer division)
  if (ownership_ == PixelOwnership::Ranges) return int(((q + 1) * R - 1) / pixels_);
  const uint64_t base = pixels_ / R, extra = pixels_ % R, wide = extra * (base + 1);
  return int(q < wide ? q / (base + 1) : extra + (q - wide) / base);
}

uint64_t PixelRanges::pixelAt(uint64_t q) const {
  const int r = owner(q);
  if (ownership_ == PixelOwnership::Ranges) return q;
  return (q - begin(r)) * uint64_t(ranks_) + uint64_t(r);
}

uint64_t PixelRanges::positionOf(uint64_t p) const {
  if (p >= pixels_)
    throw std::out_of_range("pixel " + std::to_string(p) + " outside an image of " +
                            std::to_string(pixels_));
  if (ownership_ == PixelOwnership::Ranges || ranks_ == 1) return p;
  return dcInterleavedPosition(uint32_t(p), uint32_t(ranks_), byRanks(), base(), extra());
}

int PixelRanges::ownerOfPixel(uint64_t p) const {
  if (ownership_ == PixelOwnership::Ranges) return owner(p);
  if (p >= pixels_)
    throw std::out_of_range("pixel " + std::to_string(p) + " outside an image of " +
                            std::to_string(pixels_));
  return int(p % uint64_t(ranks_));
}

uint32_t counterBits(uint64_t maxListLength) {
  if (maxListLength < 4) return 2;
  if (maxListLength < 16) return 4;
  if (maxListLength < 256) return 8;
  return 32;
}

uint32_t chooseCounterBits(uint64_t maxListLength, uint32_t forced) {
  if (forced == 0) return counterBits(maxListLength);
  if (forced != 2 && forced != 4 && forced != 8 && forced != 32)
    throw std::invalid_argument("counter encoding must be 2, 4, 8 or 32 bits, not " +
                                std::to_string(forced));
  if (forced < 32 && maxListLength >= (uint64_t(1) << forced))
    throw std::invalid_argument(std::to_string(forced) + "-bit counters cannot hold the longest " +
                                "fragment list (" + std::to_string(maxListLength) + ")");
  return forced;
}

uint64_t Transfer::sendTotal() const {
  return std::accumulate(sendBytes.begin(), sendBytes.end(), uint64_t(0));
}

uint64_t Transfer::recvTotal() const {
  return std::accumulate(recvBytes.begin(), recvBytes.end(), uint64_t(0));
}

uint64_t Transfer::sentToOthers(int self) const {
  return sendTotal() - sendBytes[size_t(self)];
}

CountExchange planCountExchange(const PixelRanges& ranges, int rank, uint32_t bits) {
  const size_t R = size_t(ranges.ranks());
  CountExchange c;
  c.bits = bits;
  c.sendWordBegin.assign(R + 1, 0);
  Transfer& t = c.transfer;
  t.sendBytes.resize(R);
  t.sendOffsets.resize(R);
  for (size_t d = 0; d < R; ++d) {
    const uint64_t n = ranges.count(int(d));
    c.sendWordBegin[d + 1] = c.sendWordBegin[d] + encodedWords(n, bits);
    t.sendBytes[d] = encodedBytes(n, bits);
    t.sendOffsets[d] = c.sendWordBegin[d] * 4;
  }
  const uint64_t mine = ranges.count(rank);
  c.wordsPerSource = encodedWords(mine, bits);
  t.recvBytes.assign(R, encodedBytes(mine, bits));
  t.recvOffsets.resize(R);
  for (size_t s = 0; s < R; ++s) t.recvOffsets[s] = s * c.wordsPerSource * 4;
  return c;
}

Transfer planFragmentExchange(std::span<const uint64_t> sendBegin,
                              std::span<const uint64_t> recvBegin, uint32_t fragmentBytes) {
  if (sendBegin.size() != recvBegin.size() || sendBegin.size() < 2)
    throw std::invalid_argument("fragment exchange: boundaries need ranks + 1 entries");
  const size_t R = sendBegin.size() - 1;
  Transfer t;
  for (auto* v : {&t.sendBytes, &t.sendOffsets, &t.recvBytes, &t.recvOffsets}) v->resize(R);
  for (size_t i = 0; i < R; ++i) {
    if (sendBegin[i + 1] < sendBegin[i] || recvBegin[i + 1] < recvBegin[i])
      throw std::logic_error("fragment exchange: boundaries must not decrease");
    t.sendOffsets[i] = sendBegin[i] * fragmentBytes;
    t.sendBytes[i] = (sendBegin[i + 1] - sendBegin[i]) * fragmentBytes;
    t.recvOffsets[i] = recvBegin[i] * fragmentBytes;
    t.recvBytes[i] = (recvBegin[i + 1] - recvBegin[i]) * fragmentBytes;
  }
  return t;
}

std::vector<uint64_t> fragmentsPerDestination(const PixelRanges& ranges,
                                              std::span<const uint32_t> counts) {
  if (counts.size() != ranges.pixels())
    throw std::invalid_argument("fragment counts: " + std::to_string(counts.size()) +
                                " values for " + std::to_string(ranges.pixels()) + " pixels");
  std::vector<uint64_t> out(size_t(ranges.ranks()), 0);
  for (uint64_t p = 0; p < counts.size(); ++p) out[size_t(ranges.ownerOfPixel(p))] += counts[p];
  return out;
}

}  // namespace sm::comp
