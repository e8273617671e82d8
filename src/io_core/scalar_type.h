// The numeric element types of VTK arrays, how each format names them, and loading one value from
// unaligned bytes in either byte order.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string_view>
#include <type_traits>

namespace sm::io {

enum class ScalarType : uint8_t {
  Int8,
  UInt8,
  Int16,
  UInt16,
  Int32,
  UInt32,
  Int64,
  UInt64,
  Float32,
  Float64
};

// VTK XML names: "Int8" .. "UInt64", "Float32", "Float64" (also the old "Char"/"Int"-style
// aliases VTK still accepts are not produced by any writer we know, so they are rejected).
std::optional<ScalarType> scalarTypeFromXml(std::string_view name);
// Legacy .vtk names, case-insensitive: char, unsigned_char, short, ..., float, double, vtkIdType,
// vtktypeint64, vtktypeuint32, ... ("bit" is handled by the legacy reader itself).
std::optional<ScalarType> scalarTypeFromLegacy(std::string_view name);
std::string_view scalarTypeName(ScalarType t);  // the XML name
size_t scalarSize(ScalarType t);
constexpr bool isFloatType(ScalarType t) {
  return t == ScalarType::Float32 || t == ScalarType::Float64;
}

// Calls f(std::type_identity<T>{}) with the C++ type of `t`.
template <class F>
decltype(auto) visitScalarType(ScalarType t, F&& f) {
  switch (t) {
    case ScalarType::Int8:
      return f(std::type_identity<int8_t>{});
    case ScalarType::UInt8:
      return f(std::type_identity<uint8_t>{});
    case ScalarType::Int16:
      return f(std::type_identity<int16_t>{});
    case ScalarType::UInt16:
      return f(std::type_identity<uint16_t>{});
    case ScalarType::Int32:
      return f(std::type_identity<int32_t>{});
    case ScalarType::UInt32:
      return f(std::type_identity<uint32_t>{});
    case ScalarType::Int64:
      return f(std::type_identity<int64_t>{});
    case ScalarType::UInt64:
      return f(std::type_identity<uint64_t>{});
    case ScalarType::Float32:
      return f(std::type_identity<float>{});
    case ScalarType::Float64:
      break;
  }
  return f(std::type_identity<double>{});
}

template <class T>
T byteSwap(T v) {
  if constexpr (sizeof(T) == 1) {
    return v;
  } else {
    using U = std::conditional_t<sizeof(T) == 2, uint16_t,
                                 std::conditional_t<sizeof(T) == 4, uint32_t, uint64_t>>;
    U u = std::bit_cast<U>(v);
    if constexpr (sizeof(T) == 2) u = __builtin_bswap16(u);
    if constexpr (sizeof(T) == 4) u = __builtin_bswap32(u);
    if constexpr (sizeof(T) == 8) u = __builtin_bswap64(u);
    return std::bit_cast<T>(u);
  }
}

// One value of type T from possibly unaligned bytes; Swap: the bytes are in the other order.
template <class T, bool Swap>
inline T loadAs(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  if constexpr (Swap) v = byteSwap(v);
  return v;
}

template <class T>
inline T loadAs(const uint8_t* p, bool swap) {
  return swap ? loadAs<T, true>(p) : loadAs<T, false>(p);
}

// Whether data written in big-endian (or little-endian) order needs swapping on this machine.
constexpr bool needsSwap(bool bigEndian) {
  return bigEndian != (std::endian::native == std::endian::big);
}

}  // namespace sm::io
