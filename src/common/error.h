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

// Errors caused by the content of an input file: the message starts with the file name.
class FileError : public Error {
 public:
  template <typename... Args>
  FileError(const std::string& file, Args&&... args)
      : Error(concat(file, ": ", std::forward<Args>(args)...)), file_(file) {}
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

}  // namespace sm
