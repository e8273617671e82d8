// User-facing errors: one line that names the file, element or option at fault. Thrown for bad
// input, impossible options and missing capabilities; caught at the command-line boundary, which
// prints "shellmarch: error: <what>" and exits non-zero.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace sm {

template <typename... Args>
std::string concat(Args&&... args) {
  std::ostringstream os;
  (os << ... << std::forward<Args>(args));
  return os.str();
}

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
  template <typename A, typename B, typename... Rest>
  Error(A&& a, B&& b, Rest&&... rest)
      : std::runtime_error(
            concat(std::forward<A>(a), std::forward<B>(b), std::forward<Rest>(rest)...)) {}
};

// A message as one printable line: control characters (a newline that would forge another line,
// a terminal escape sequence) become \xNN. File names and names inside files are other people's
// bytes, and reach a terminal through error messages.
inline std::string printableLine(std::string text) {
  static const char* hex = "0123456789abcdef";
  for (size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c != 0x7f) continue;
    text.replace(i, 1, std::string{'\\', 'x', hex[c >> 4], hex[c & 15]});
    i += 3;
  }
  return text;
}

// Errors caused by the content of an input file: the message starts with the file name.
class FileError : public Error {
 public:
  template <typename... Args>
  FileError(const std::string& file, Args&&... args)
      : Error(printableLine(concat(file, ": ", std::forward<Args>(args)...))), file_(file) {}
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

}  // namespace sm
