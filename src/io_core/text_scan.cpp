#include "io_core/text_scan.h"

#include <algorithm>
#include <cctype>
#include <charconv>

#include "common/error.h"

namespace sm::io {
namespace {

template <class T>
bool parseWhole(std::string_view tok, T& out) {
  if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);  // from_chars rejects '+'
  if (tok.empty()) return false;
  auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), out);
  return ec == std::errc() && end == tok.data() + tok.size();
}

}  // namespace

std::string_view TextCursor::token() {
  skipSpace();
  const char* b = pos_;
  while (pos_ < end_ && !isSpace(*pos_)) ++pos_;
  return {b, static_cast<size_t>(pos_ - b)};
}

std::string printable(std::string_view token) {
  std::string r(token.substr(0, 40));
  for (char& c : r)
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
  return r;
}

bool parseNumber(std::string_view token, int64_t& out) {
  return parseWhole(token, out);
}
bool parseNumber(std::string_view token, uint64_t& out) {
  return parseWhole(token, out);
}

bool parseNumber(std::string_view token, double& out) {
  if (parseWhole(token, out)) return true;
  // Fortran writes exponents as D: retry with E, in a small local copy.
  if (token.size() > 64 || token.find_first_of("dD") == std::string_view::npos) return false;
  char buf[64];
  std::transform(token.begin(), token.end(), buf,
                 [](char c) { return c == 'd' || c == 'D' ? 'e' : c; });
  return parseWhole(std::string_view(buf, token.size()), out);
}

void throwIfSectionEndsEarly(std::string_view token, uint64_t read, uint64_t declared,
                             const std::string& source, std::string_view what) {
  if (double v = 0; token.empty() || parseNumber(token, v)) return;
  if (std::all_of(token.begin(), token.end(),
                  [](char c) { return std::isalpha(uint8_t(c)) || c == '_'; }))
    throw FileError(source, what, ": found '", printable(token), "' after ", read, " of the ",
                    declared, " values its header declares (the section holds fewer)");
}

template <class T>
void scanNumbers(TextCursor& cursor, T* out, uint64_t n, const std::string& source,
                 std::string_view what, bool sectioned) {
  for (uint64_t i = 0; i < n; ++i) {
    std::string_view tok = cursor.token();
    if (tok.empty())
      throw FileError(source, what, ": the text ends after ", i, " of ", n, " values");
    if (parseNumber(tok, out[i])) continue;
    if (sectioned) throwIfSectionEndsEarly(tok, i, n, source, what);
    throw FileError(source, what, ": value ", i, " ('", printable(tok), "') is not a ",
                    std::is_floating_point_v<T> ? "number" : "whole number");
  }
}

template void scanNumbers<int64_t>(TextCursor&, int64_t*, uint64_t, const std::string&,
                                   std::string_view, bool);
template void scanNumbers<uint64_t>(TextCursor&, uint64_t*, uint64_t, const std::string&,
                                    std::string_view, bool);
template void scanNumbers<double>(TextCursor&, double*, uint64_t, const std::string&,
                                  std::string_view, bool);

}  // namespace sm::io
