#include "io_core/scalar_type.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <string>

namespace sm::io {
namespace {

struct NamedType {
  std::string_view name;
  ScalarType type;
};

constexpr std::array<NamedType, 10> kXmlNames = {{{"Int8", ScalarType::Int8},
                                                  {"UInt8", ScalarType::UInt8},
                                                  {"Int16", ScalarType::Int16},
                                                  {"UInt16", ScalarType::UInt16},
                                                  {"Int32", ScalarType::Int32},
                                                  {"UInt32", ScalarType::UInt32},
                                                  {"Int64", ScalarType::Int64},
                                                  {"UInt64", ScalarType::UInt64},
                                                  {"Float32", ScalarType::Float32},
                                                  {"Float64", ScalarType::Float64}}};

// Legacy names as vtkDataReader accepts them (compared lower-cased). "long" is 64-bit: the
// legacy writer only emits it on platforms where long is 64-bit (LP64), like this one.
constexpr std::array<NamedType, 24> kLegacyNames = {{{"char", ScalarType::Int8},
                                                     {"signed_char", ScalarType::Int8},
                                                     {"unsigned_char", ScalarType::UInt8},
                                                     {"short", ScalarType::Int16},
                                                     {"unsigned_short", ScalarType::UInt16},
                                                     {"int", ScalarType::Int32},
                                                     {"unsigned_int", ScalarType::UInt32},
                                                     {"long", ScalarType::Int64},
                                                     {"unsigned_long", ScalarType::UInt64},
                                                     {"long_long", ScalarType::Int64},
                                                     {"unsigned_long_long", ScalarType::UInt64},
                                                     {"vtkidtype", ScalarType::Int64},
                                                     {"float", ScalarType::Float32},
                                                     {"double", ScalarType::Float64},
                                                     {"vtktypeint8", ScalarType::Int8},
                                                     {"vtktypeuint8", ScalarType::UInt8},
                                                     {"vtktypeint16", ScalarType::Int16},
                                                     {"vtktypeuint16", ScalarType::UInt16},
                                                     {"vtktypeint32", ScalarType::Int32},
                                                     {"vtktypeuint32", ScalarType::UInt32},
                                                     {"vtktypeint64", ScalarType::Int64},
                                                     {"vtktypeuint64", ScalarType::UInt64},
                                                     {"vtktypefloat32", ScalarType::Float32},
                                                     {"vtktypefloat64", ScalarType::Float64}}};

}  // namespace

std::optional<ScalarType> scalarTypeFromXml(std::string_view name) {
  for (const auto& n : kXmlNames)
    if (n.name == name) return n.type;
  return std::nullopt;
}

std::optional<ScalarType> scalarTypeFromLegacy(std::string_view name) {
  std::string lower(name);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const auto& n : kLegacyNames)
    if (n.name == lower) return n.type;
  return std::nullopt;
}

std::string_view scalarTypeName(ScalarType t) {
  return kXmlNames[static_cast<size_t>(t)].name;
}

size_t scalarSize(ScalarType t) {
  return visitScalarType(t, [](auto tag) { return sizeof(typename decltype(tag)::type); });
}

}  // namespace sm::io
