#include "io/legacy_scanner.h"

#include <algorithm>
#include <cctype>

#include "common/error.h"

namespace sm::io {
namespace {

constexpr uint64_t kMaxValues = uint64_t(1) << 58;

int hexValue(char c) {
  return std::isdigit(static_cast<unsigned char>(c)) ? c - '0' : std::tolower(c) - 'a' + 10;
}

}  // namespace

std::string lowerCase(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return r;
}

std::string decodeVtkName(std::string_view s) {
  std::string r;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && std::isxdigit(static_cast<unsigned char>(s[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(s[i + 2]))) {
      r += static_cast<char>(hexValue(s[i + 1]) * 16 + hexValue(s[i + 2]));
      i += 2;
    } else {
      r += s[i];
    }
  }
  return r;
}

LegacyScanner::LegacyScanner(std::span<const uint8_t> bytes, const std::string& source)
    : src_(source),
      begin_(reinterpret_cast<const char*>(bytes.data())),
      cur_(begin_, begin_ + bytes.size()) {}

void LegacyScanner::fail(std::string_view what) const {
  throw FileError(src_, what, " (at byte ", cur_.pos() - begin_, ")");
}

std::string_view LegacyScanner::line() {
  const char* b = cur_.pos();
  const char* e = std::find(b, cur_.end(), '\n');
  cur_.setPos(e == cur_.end() ? e : e + 1);
  std::string_view l(b, static_cast<size_t>(e - b));
  while (!l.empty() && isSpace(l.back())) l.remove_suffix(1);
  return l;
}

bool LegacyScanner::acceptKeyword(std::string_view keyword) {
  const char* save = cur_.pos();
  if (lowerCase(cur_.token()) == keyword) return true;
  cur_.setPos(save);
  return false;
}

uint64_t LegacyScanner::count(std::string_view tok, std::string_view what) const {
  uint64_t v = 0;
  if (!parseNumber(tok, v) || v > kMaxValues)
    fail(concat(what, " '", printable(tok), "' is not a count"));
  return v;
}

NumericArray LegacyScanner::data(std::string_view typeName, uint32_t comps, uint64_t tuples,
                                 const std::string& what, bool keep) {
  const std::string t = lowerCase(typeName);
  if (comps == 0 || tuples > kMaxValues / comps) fail(concat(what, ": impossible size"));
  const uint64_t n = tuples * comps;
  if (t == "bit") return bits(n, comps, tuples, what, keep);
  if (t == "string" || t == "utf8_string") {
    skipStrings(n, what);
    return {};
  }
  auto type = scalarTypeFromLegacy(t);
  if (!type) fail(concat(what, ": unknown data type '", printable(typeName), "'"));
  if (binary_) {
    const uint64_t bytes = n * scalarSize(*type);
    if (bytes > cur_.remaining())
      fail(concat(what, ": needs ", bytes, " bytes but the file ends after ", cur_.remaining()));
    const uint8_t* p = reinterpret_cast<const uint8_t*>(cur_.pos());
    cur_.setPos(cur_.pos() + bytes);
    return NumericArray::view(*type, comps, tuples, p, needsSwap(true));
  }
  if (n > maxNumbersInText(cur_.remaining()))
    fail(concat(what, ": declares ", n, " values but the file is too short for them"));
  if (!keep) {  // skipped, not parsed; a word is still caught, as it ends the section early
    for (uint64_t i = 0; i < n; ++i) {
      const std::string_view tok = cur_.token();
      if (tok.empty()) fail(concat(what, ": the file ends after ", i, " of ", n, " values"));
      if (std::isalpha(uint8_t(tok[0]))) throwIfSectionEndsEarly(tok, i, n, src_, what);
    }
    return {};
  }
  ByteBuffer buf = ByteBuffer::allocate(std::max<uint64_t>(n, 1) * 8);
  ScalarType stored = ScalarType::Int64;
  if (isFloatType(*type)) {
    stored = ScalarType::Float64;
    scanNumbers(cur_, reinterpret_cast<double*>(buf.data()), n, src_, what, true);
  } else if (*type == ScalarType::UInt64) {
    stored = ScalarType::UInt64;
    scanNumbers(cur_, reinterpret_cast<uint64_t*>(buf.data()), n, src_, what, true);
  } else {
    scanNumbers(cur_, reinterpret_cast<int64_t*>(buf.data()), n, src_, what, true);
  }
  return NumericArray::owned(stored, comps, tuples, std::move(buf), false);
}

// Bit arrays: packed most significant bit first when binary, 0/1 tokens when ascii.
NumericArray LegacyScanner::bits(uint64_t n, uint32_t comps, uint64_t tuples,
                                 const std::string& what, bool keep) {
  const uint64_t bytes = binary_ ? (n + 7) / 8 : 0;
  if (binary_ ? bytes > cur_.remaining() : n > maxNumbersInText(cur_.remaining()))
    fail(concat(what, ": the file is too short for ", n, " bits"));
  ByteBuffer buf = ByteBuffer::allocate(std::max<uint64_t>(n, 1));
  const char* p = cur_.pos();
  for (uint64_t i = 0; i < n; ++i) {
    if (binary_) {
      buf.data()[i] = (static_cast<uint8_t>(p[i / 8]) >> (7 - i % 8)) & 1;
    } else {
      std::string_view tok = cur_.token();
      if (tok.empty()) fail(concat(what, ": the file ends inside a bit array"));
      buf.data()[i] = tok != "0";
    }
  }
  if (binary_) cur_.setPos(p + bytes);
  if (!keep) return {};
  return NumericArray::owned(ScalarType::UInt8, comps, tuples, std::move(buf), false);
}

// String arrays: one per line in ascii; in binary each string has a big-endian length whose
// first byte's top two bits give its width (11: 6 bits, 10: 14 bits, 01: 30 bits, 00: 8 bytes).
void LegacyScanner::skipStrings(uint64_t n, const std::string& what) {
  for (uint64_t i = 0; i < n; ++i) {
    if (cur_.remaining() == 0) fail(concat(what, ": the file ends inside a string array"));
    if (!binary_) {
      line();
      continue;
    }
    const uint8_t* p = reinterpret_cast<const uint8_t*>(cur_.pos());
    const int tag = p[0] >> 6;
    const int width = tag == 3 ? 1 : tag == 2 ? 2 : tag == 1 ? 4 : 8;
    if (cur_.remaining() < size_t(width))
      fail(concat(what, ": the file ends inside a string array"));
    uint64_t len = p[0] & (width == 8 ? 0xFF : 0x3F);
    for (int k = 1; k < width; ++k) len = (len << 8) | p[k];
    if (len > cur_.remaining() - width)
      fail(concat(what, ": a string runs past the end of the file"));
    cur_.setPos(cur_.pos() + width + len);
  }
}

void LegacyScanner::skipMetadata() {
  line();  // the rest of the METADATA line
  while (cur_.remaining() > 0 && !line().empty()) {
  }
}

void LegacyScanner::skipMetadataIfPresent() {
  if (acceptKeyword("metadata")) skipMetadata();
}

}  // namespace sm::io
