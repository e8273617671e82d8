// Whitespace-separated numbers in text (ascii VTK XML, legacy .vtk, ascii .ugrid), parsed with
// std::from_chars: no locale, no allocation, no per-token strings.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace sm::io {

inline bool isSpace(char c) {
  return c == ' ' || c == '\n' || c == '\r' || c == '\t' || c == '\f' || c == '\v';
}

class TextCursor {
 public:
  TextCursor(const char* begin, const char* end) : pos_(begin), end_(end) {}
  explicit TextCursor(std::string_view text) : pos_(text.data()), end_(text.data() + text.size()) {}

  // The next whitespace-separated token; empty at the end of the text.
  std::string_view token();
  void skipSpace() {
    while (pos_ < end_ && isSpace(*pos_)) ++pos_;
  }
  bool atEnd() {
    skipSpace();
    return pos_ == end_;
  }
  const char* pos() const { return pos_; }
  const char* end() const { return end_; }
  void setPos(const char* p) { pos_ = p; }
  size_t remaining() const { return static_cast<size_t>(end_ - pos_); }

 private:
  const char* pos_;
  const char* end_;
};

// Parses a whole token as a number: integers for integral T, decimal floating point (also "nan",
// "inf", a leading '+', and Fortran's "1.5D+03") for double. False if the token is not one.
bool parseNumber(std::string_view token, int64_t& out);
bool parseNumber(std::string_view token, uint64_t& out);
bool parseNumber(std::string_view token, double& out);

// Reads exactly n numbers into out; throws sm::FileError(source, what, ...) when a token is not
// a number or the text ends early. Callers check that n is plausible for the text length first.
// `sectioned`: the text is a legacy file's, where a word among the values is most often the next
// section's keyword (the header declared more values than the section holds), and is named so.
template <class T>
void scanNumbers(TextCursor& cursor, T* out, uint64_t n, const std::string& source,
                 std::string_view what, bool sectioned = false);

// In a legacy file, a word where a section's values should be: most often the next section's
// keyword, the header having declared more values than the section holds. Throws
// sm::FileError(source, what, ...) saying so when `token` is a word (not a number), after
// `read` of `declared` values.
void throwIfSectionEndsEarly(std::string_view token, uint64_t read, uint64_t declared,
                             const std::string& source, std::string_view what);

// A token as it may appear in a one-line message: at most 40 characters, unprintable ones as '?'.
std::string printable(std::string_view token);

// At most how many numbers text of this many bytes can hold (each needs a character and a
// separator): lets callers reject absurd declared counts before allocating.
constexpr uint64_t maxNumbersInText(uint64_t bytes) {
  return bytes / 2 + 1;
}

}  // namespace sm::io
