#include "io_core/numeric_array.h"

#include "io_core/array_plan.h"

#include <sys/mman.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <new>
#include <string>

#include "common/error.h"
#include "common/log.h"
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

namespace {

// The finite values' extent, in double.
struct Span {
  double lo = INFINITY, hi = -INFINITY;
  void add(double v) {
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  }
  void add(const Span& o) { lo = std::min(lo, o.lo), hi = std::max(hi, o.hi); }
};

// Values stored as 32-bit floats keep 24 bits: 1e12 + 0..1000 all become 999999995904, and a
// render shows one colour without saying why. Warned when the span holds fewer than 256 float
// steps, the colour table's resolution.
void warnIfFloatsCannotResolve(const Span& s, const ArrayName* array) {
  if (!array || !(s.lo < s.hi)) return;
  const double ulp = std::ldexp(1.0, std::ilogb(std::max(std::abs(s.lo), std::abs(s.hi))) - 23);
  if (s.hi - s.lo >= 256 * ulp) return;
  if (!log::firstTime(
          concat("float precision ", array->kind, ' ', splitStepName(array->name).base)))
    return;
  const int levels = int((s.hi - s.lo) / ulp) + 1;
  log::warning(array->source, ": ", array->kind, " array '", array->name, "': values span ",
               s.hi - s.lo, " at ", s.hi, ", where 32-bit floats step by ", ulp, ": ",
               levels == 1 ? std::string("they show as one value")
                           : concat("at most ", levels, " levels show"),
               "; write the field less an offset to see it whole");
}

}  // namespace

std::vector<float> toFloats(const NumericArray& a, int component, unsigned threads,
                            const ArrayName* name) {
  std::vector<float> out(a.tuples);
  const uint32_t nc = a.components;
  std::mutex mutex;
  Span span;
  visitArray(a, [&](auto tag, auto swap) {
    using T = typename decltype(tag)::type;
    constexpr bool kSwap = decltype(swap)::value;
    // Float input and 16-bit and smaller integers are held exactly; only wider types can lose.
    constexpr bool kMayLose = !std::is_same_v<T, float> && sizeof(T) > 2;
    const uint8_t* d = a.data;
    parallelFor(
        static_cast<int64_t>(a.tuples),
        [&](int64_t b, int64_t e) {
          Span local;
          if (component >= 0 || nc == 1) {
            const uint64_t c = component >= 0 ? uint64_t(component) : 0;
            for (int64_t i = b; i < e; ++i) {
              const T v = loadAs<T, kSwap>(d + (i * nc + c) * sizeof(T));
              out[i] = static_cast<float>(v);
              if constexpr (kMayLose) local.add(static_cast<double>(v));
            }
          } else {
            for (int64_t i = b; i < e; ++i) {
              double s = 0.0;
              for (uint32_t c = 0; c < nc; ++c) {
                double v = static_cast<double>(loadAs<T, kSwap>(d + (i * nc + c) * sizeof(T)));
                s += v * v;
              }
              out[i] = static_cast<float>(std::sqrt(s));
              if constexpr (kMayLose) local.add(std::sqrt(s));
            }
          }
          std::lock_guard<std::mutex> lock(mutex);
          span.add(local);
        },
        threads, kParallelMin);
  });
  warnIfFloatsCannotResolve(span, name);
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
