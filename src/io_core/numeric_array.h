// A decoded array of numbers as a reader found it (tuples x components values of one scalar type,
// packed, in the file's byte order) and its conversions to what the mesh stores. Binary data is
// viewed in place in the input; only ascii and compressed data need a buffer of their own.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <glm/vec3.hpp>

#include "io_core/scalar_type.h"

namespace sm::io {

// Uninitialised bytes (no memset for buffers that are filled right away). Large buffers are
// aligned to 2 MiB and marked for transparent huge pages: filling hundreds of megabytes of
// decompressed data otherwise costs a page fault and a page clear per 4 KiB.
struct ByteBufferFree {
  bool huge = false;
  void operator()(uint8_t* p) const;
};

struct ByteBuffer {
  std::unique_ptr<uint8_t, ByteBufferFree> bytes;
  size_t size = 0;
  static ByteBuffer allocate(size_t n);
  uint8_t* data() { return bytes.get(); }
  const uint8_t* data() const { return bytes.get(); }
};

struct NumericArray {
  ScalarType type = ScalarType::Float64;
  uint32_t components = 1;
  uint64_t tuples = 0;
  bool swap = false;              // byte order differs from the host's
  const uint8_t* data = nullptr;  // into the input, or into storage
  ByteBuffer storage;

  uint64_t numValues() const { return tuples * components; }
  uint64_t numBytes() const { return numValues() * scalarSize(type); }

  static NumericArray view(ScalarType type, uint32_t components, uint64_t tuples,
                           const uint8_t* data, bool swap);
  static NumericArray owned(ScalarType type, uint32_t components, uint64_t tuples, ByteBuffer bytes,
                            bool swap);
};

// Calls f(std::type_identity<T>{}, std::bool_constant<Swap>{}) for the array's type and order.
template <class F>
decltype(auto) visitArray(const NumericArray& a, F&& f) {
  return visitScalarType(a.type, [&](auto tag) {
    return a.swap ? f(tag, std::true_type{}) : f(tag, std::false_type{});
  });
}

// Values of a point field: component `component`, or for component < 0 the single value of a
// one-component array or the magnitude of a vector. Non-finite values pass through. threads: 0
// for all cores. With `name`, warns when the values' span is too narrow for their magnitude in
// 32-bit floats (1e12 + 0..1000 becomes one value), once per run for each field (its pieces and
// steps repeat the array).
struct ArrayName {
  std::string_view source;  // the file
  std::string_view kind;    // "point" or "cell"
  std::string_view name;    // the array's, "p@t3" for step 3 of field "p"
};
std::vector<float> toFloats(const NumericArray& a, int component, unsigned threads = 0,
                            const ArrayName* name = nullptr);
// Tuples of three components as points (callers check components == 3).
std::vector<glm::dvec3> toPoints(const NumericArray& a, unsigned threads = 0);
// Integer values (cell types, offsets, cluster ids); floating-point values must be whole
// numbers and unsigned ones must fit in int64, else sm::FileError(source, what, ...).
std::vector<int64_t> toInt64(const NumericArray& a, const std::string& source,
                             std::string_view what);

}  // namespace sm::io
