// 64-bit content hashing for cache keys and checksums (not cryptographic).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace sm {

class Hasher {
 public:
  Hasher& bytes(const void* data, size_t size);
  template <typename T>
  Hasher& pod(const T& v) {
    return bytes(&v, sizeof v);
  }
  template <typename T>
  Hasher& span(std::span<const T> v) {
    pod(uint64_t(v.size()));
    return bytes(v.data(), v.size_bytes());
  }
  Hasher& str(std::string_view s) {
    pod(uint64_t(s.size()));
    return bytes(s.data(), s.size());
  }
  uint64_t digest() const;

 private:
  uint64_t h_ = 0x9E3779B97F4A7C15ull;
  uint64_t n_ = 0;
};

uint64_t hashBytes(const void* data, size_t size);

}  // namespace sm
