#include "common/hash.h"

#include <cstring>

namespace sm {
namespace {
inline uint64_t mix(uint64_t x) {
  x ^= x >> 30;
  x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 27;
  x *= 0x94D049BB133111EBull;
  x ^= x >> 31;
  return x;
}
}  // namespace

// Word-at-a-time mixing: fast enough to hash gigabytes of mesh arrays at memory bandwidth.
Hasher& Hasher::bytes(const void* data, size_t size) {
  const auto* p = static_cast<const uint8_t*>(data);
  size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    uint64_t w;
    std::memcpy(&w, p + i, 8);
    h_ = mix(h_ ^ w) + 0x632BE59BD9B4E019ull;
  }
  uint64_t tail = 0;
  if (size > i) std::memcpy(&tail, p + i, size - i);  // an empty span's data() may be null
  h_ = mix(h_ ^ tail ^ (uint64_t(size - i) << 56));
  n_ += size;
  return *this;
}

uint64_t Hasher::digest() const {
  return mix(h_ ^ n_);
}

uint64_t hashBytes(const void* data, size_t size) {
  return Hasher().bytes(data, size).digest();
}

}  // namespace sm
