#include "io/numeric_array.h"

#include <sys/mman.h>

#include <cmath>
#include <limits>
#include <new>

#include "common/error.h"
#include "common/parallel.h"

namespace sm::io {
namespace {

constexpr int64_t kParallelMin = 1 << 16;  // below this, threads cost more than they save
constexpr size_t kHugePage = size_t(2) << 20;
constexpr size_t kHugeMin = size_t(8) << 20;

}  // namespace

void ByteBufferFree::operator()(uint8_t* p) const {
  if (huge)
    ::operator delete[](p, std::align_val_t(kHugePage));
  else
    delete[] p;
}

ByteBuffer ByteBuffer::allocate(size_t n) {
  ByteBuffer b;
  b.size = n;
  if (n < kHugeMin) {
    b.bytes = std::unique_ptr<uint8_t, ByteBufferFree>(new uint8_t[n], ByteBufferFree{false});
    return b;
  }
  auto* p = static_cast<uint8_t*>(::operator new[](n, std::align_val_t(kHugePage)));
  b.bytes = std::unique_ptr<uint8_t, ByteBufferFree>(p, ByteBufferFree{true});
  ::madvise(p, (n + kHugePage - 1) / kHugePage * kHugePage, MADV_HUGEPAGE);  // advisory only
  return b;
}

NumericArray NumericArray::view(ScalarType type, uint32_t components, uint64_t tuples,
                                const uint8_t* data, bool swap) {
  NumericArray a;
  a.type = type;
  a.components = components;
  a.tuples = tuples;
  a.swap = swap;
  a.data = data;
  return a;
}

NumericArray NumericArray::owned(ScalarType type, uint32_t components, uint64_t tuples,
                                 ByteBuffer bytes, bool swap) {
  NumericArray a = view(type, components, tuples, bytes.data(), swap);
  a.storage = std::move(bytes);
  return a;
}

std::vector<float> toFloats(const NumericArray& a, int component, unsigned threads) {
  std::vector<float> out(a.tuples);
  const uint32_t nc = a.components;
  visitArray(a, [&](auto tag, auto swap) {
    using T = typename decltype(tag)::type;
    constexpr bool kSwap = decltype(swap)::value;
    const uint8_t* d = a.data;
    parallelFor(
        static_cast<int64_t>(a.tuples),
        [&](int64_t b, int64_t e) {
          if (component >= 0 || nc == 1) {
            const uint64_t c = component >= 0 ? uint64_t(component) : 0;
            for (int64_t i = b; i < e; ++i)
              out[i] = static_cast<float>(loadAs<T, kSwap>(d + (i * nc + c) * sizeof(T)));
          } else {
            for (int64_t i = b; i < e; ++i) {
              double s = 0.0;
              for (uint32_t c = 0; c < nc; ++c) {
                double v = static_cast<double>(loadAs<T, kSwap>(d + (i * nc + c) * sizeof(T)));
                s += v * v;
              }
              out[i] = static_cast<float>(std::sqrt(s));
            }
          }
        },
        threads, kParallelMin);
  });
  return out;
}

std::vector<glm::dvec3> toPoints(const NumericArray& a, unsigned threads) {
  std::vector<glm::dvec3> out(a.tuples);
  visitArray(a, [&](auto tag, auto swap) {
    using T = typename decltype(tag)::type;
    constexpr bool kSwap = decltype(swap)::value;
    const uint8_t* d = a.data;
    parallelFor(
        static_cast<int64_t>(a.tuples),
        [&](int64_t b, int64_t e) {
          for (int64_t i = b; i < e; ++i) {
            const uint8_t* p = d + i * 3 * sizeof(T);
            out[i] = {static_cast<double>(loadAs<T, kSwap>(p)),
                      static_cast<double>(loadAs<T, kSwap>(p + sizeof(T))),
                      static_cast<double>(loadAs<T, kSwap>(p + 2 * sizeof(T)))};
          }
        },
        threads, kParallelMin);
  });
  return out;
}

std::vector<int64_t> toInt64(const NumericArray& a, const std::string& source,
                             std::string_view what) {
  const uint64_t n = a.numValues();
  std::vector<int64_t> out(n);
  visitArray(a, [&](auto tag, auto swap) {
    using T = typename decltype(tag)::type;
    constexpr bool kSwap = decltype(swap)::value;
    for (uint64_t i = 0; i < n; ++i) {
      T v = loadAs<T, kSwap>(a.data + i * sizeof(T));
      if constexpr (std::is_floating_point_v<T>) {
        // 2^63 is exactly representable; anything at or beyond it does not fit.
        if (!(std::trunc(v) == v && std::fabs(double(v)) < 9223372036854775808.0))
          throw FileError(source, what, ": value ", i, " (", v, ") is not a whole number");
      } else if constexpr (std::is_same_v<T, uint64_t>) {
        if (v > uint64_t(std::numeric_limits<int64_t>::max()))
          throw FileError(source, what, ": value ", i, " (", v, ") is out of range");
      }
      out[i] = static_cast<int64_t>(v);
    }
  });
  return out;
}

}  // namespace sm::io
