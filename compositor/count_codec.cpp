#include "compositor/count_codec.h"

#include <string>

#include "comm/communicator.h"

namespace sm::comp {

void packCounterWords(std::span<const uint32_t> counters, uint32_t bits,
                      std::vector<uint32_t>& words) {
  if (bits == 32) {
    words.assign(counters.begin(), counters.end());
    return;
  }
  const uint64_t perWord = 32 / bits;
  words.assign((counters.size() + perWord - 1) / perWord, 0u);
  for (uint64_t i = 0; i < counters.size(); ++i)
    words[i / perWord] |= counters[i] << ((i % perWord) * bits);
}

namespace {

// Calls record(first zero, first literal, end of literals) for each record of the code.
template <typename Record>
void forEachZeroRun(std::span<const uint32_t> words, Record record) {
  const size_t n = words.size();
  size_t i = 0;
  while (i < n) {
    size_t z = i;
    while (z < n && words[z] == 0) ++z;
    // Literals run to the next pair of zeros; a last single zero joins them.
    size_t e = z;
    while (e < n && (words[e] != 0 || e + 1 == n || words[e + 1] != 0)) ++e;
    record(i, z, e);
    i = e;
  }
}

}  // namespace

void appendZeroRuns(std::span<const uint32_t> words, std::vector<uint32_t>& out) {
  forEachZeroRun(words, [&](size_t i, size_t z, size_t e) {
    out.push_back(uint32_t(z - i));
    out.push_back(uint32_t(e - z));
    out.insert(out.end(), words.begin() + std::ptrdiff_t(z), words.begin() + std::ptrdiff_t(e));
  });
}

uint64_t zeroRunWords(std::span<const uint32_t> words) {
  uint64_t n = 0;
  forEachZeroRun(words, [&](size_t, size_t z, size_t e) { n += 2 + (e - z); });
  return n;
}

void expandZeroRuns(std::span<const uint32_t> code, std::span<uint32_t> words) {
  size_t at = 0, c = 0;
  while (at < words.size()) {
    if (c + 2 > code.size())
      throw comm::CommError("count exchange: a zero-run code ends after " + std::to_string(at) +
                            " of " + std::to_string(words.size()) + " words");
    const uint64_t zeros = code[c], literals = code[c + 1];
    c += 2;
    if (zeros + literals > words.size() - at || literals > code.size() - c)
      throw comm::CommError("count exchange: a zero-run record overruns its " +
                            std::to_string(words.size()) + " words");
    for (uint64_t k = 0; k < zeros; ++k) words[at++] = 0;
    for (uint64_t k = 0; k < literals; ++k) words[at++] = code[c++];
  }
  if (c != code.size())
    throw comm::CommError("count exchange: " + std::to_string(code.size() - c) +
                          " words left over after a zero-run code");
}

CountPayload choosePayload(std::span<const uint32_t> words, uint64_t denseBytes) {
  const uint64_t codeBytes = zeroRunWords(words) * 4;
  if (codeBytes < denseBytes) return {codeBytes, true};
  return {denseBytes, false};
}

}  // namespace sm::comp
