#include "io/base64.h"

#include <array>
#include <cstring>

namespace sm::io {
namespace {

constexpr uint8_t kPad = 64, kSpace = 65, kInvalid = 255;

constexpr std::array<uint8_t, 256> makeTable() {
  std::array<uint8_t, 256> t{};
  for (auto& v : t) v = kInvalid;
  const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  for (uint8_t i = 0; i < 64; ++i) t[static_cast<uint8_t>(alphabet[i])] = i;
  t['='] = kPad;
  for (char c : {' ', '\n', '\r', '\t', '\f', '\v'}) t[static_cast<uint8_t>(c)] = kSpace;
  return t;
}
constexpr std::array<uint8_t, 256> kTable = makeTable();

inline uint8_t code(char c) {
  return kTable[static_cast<uint8_t>(c)];
}

}  // namespace

bool Base64Reader::decodeQuantum(uint8_t* out, int& count) {
  uint8_t v[4];
  size_t at[4];
  int n = 0;
  while (n < 4) {
    if (pos_ >= text_.size()) return false;
    uint8_t c = code(text_[pos_++]);
    if (c == kSpace) continue;
    if (c == kInvalid) {
      bad_ = pos_ - 1;
      return false;
    }
    at[n] = pos_ - 1;
    v[n++] = c;
  }
  if (v[0] == kPad || v[1] == kPad || (v[2] == kPad && v[3] != kPad)) {
    bad_ = at[v[0] == kPad ? 0 : v[1] == kPad ? 1 : 2];
    return false;
  }
  uint32_t bits = (uint32_t(v[0]) << 18) | (uint32_t(v[1]) << 12);
  count = 1;
  if (v[2] != kPad) {
    bits |= uint32_t(v[2]) << 6;
    count = 2;
    if (v[3] != kPad) {
      bits |= v[3];
      count = 3;
    }
  }
  out[0] = static_cast<uint8_t>(bits >> 16);
  out[1] = static_cast<uint8_t>(bits >> 8);
  out[2] = static_cast<uint8_t>(bits);
  return true;
}

bool Base64Reader::read(uint8_t* out, size_t n) {
  size_t done = 0;
  while (done < n && pendingPos_ < pendingCount_) out[done++] = pending_[pendingPos_++];
  // Fast path: four alphabet characters in a row give three bytes.
  const char* t = text_.data();
  while (n - done >= 3 && pos_ + 4 <= text_.size()) {
    uint8_t a = code(t[pos_]), b = code(t[pos_ + 1]), c = code(t[pos_ + 2]), d = code(t[pos_ + 3]);
    if ((a | b | c | d) >= 64) {
      // Padding, whitespace or an invalid character: let the careful path decide.
      uint8_t q[3];
      int count = 0;
      if (!decodeQuantum(q, count)) return false;
      size_t take = std::min<size_t>(count, n - done);
      std::memcpy(out + done, q, take);
      done += take;
      continue;
    }
    uint32_t bits = (uint32_t(a) << 18) | (uint32_t(b) << 12) | (uint32_t(c) << 6) | d;
    out[done] = static_cast<uint8_t>(bits >> 16);
    out[done + 1] = static_cast<uint8_t>(bits >> 8);
    out[done + 2] = static_cast<uint8_t>(bits);
    done += 3;
    pos_ += 4;
  }
  while (done < n) {
    int count = 0;
    if (!decodeQuantum(pending_, count)) return false;
    pendingCount_ = count;
    pendingPos_ = 0;
    while (done < n && pendingPos_ < pendingCount_) out[done++] = pending_[pendingPos_++];
  }
  return true;
}

}  // namespace sm::io
