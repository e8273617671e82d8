// The lexical layer of legacy .vtk files: keywords and header lines are text, and each array's
// data follows its header line, as text (ascii files) or big-endian bytes (binary files).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "io_core/numeric_array.h"
#include "io_core/text_scan.h"

namespace sm::io {

std::string lowerCase(std::string_view s);
// VTK writes spaces and unprintable characters of names as %XX.
std::string decodeVtkName(std::string_view s);

class LegacyScanner {
 public:
  LegacyScanner(std::span<const uint8_t> bytes, const std::string& source);

  void setBinary(bool binary) { binary_ = binary; }
  bool binary() const { return binary_; }

  std::string_view token() { return cur_.token(); }
  // The rest of the current line without trailing whitespace; moves past its newline.
  std::string_view line();
  // Consumes the next token if it is `keyword` (lower case, compared case-insensitively).
  bool acceptKeyword(std::string_view keyword);
  bool atEnd() { return cur_.atEnd(); }

  // A count token (at most 2^58); anything else fails with `what`.
  uint64_t count(std::string_view token, std::string_view what) const;
  [[noreturn]] void fail(std::string_view what) const;

  // The data of one array: a view of the file when binary, parsed when ascii and `keep`,
  // skipped (returning an empty array) otherwise. Bit arrays read as UInt8 0/1; string arrays
  // are always skipped.
  NumericArray data(std::string_view type, uint32_t components, uint64_t tuples,
                    const std::string& what, bool keep);
  // METADATA blocks run to the next empty line.
  void skipMetadata();
  void skipMetadataIfPresent();

 private:
  NumericArray bits(uint64_t n, uint32_t comps, uint64_t tuples, const std::string& what,
                    bool keep);
  void skipStrings(uint64_t n, const std::string& what);

  const std::string& src_;
  const char* begin_;
  TextCursor cur_;
  bool binary_ = false;
};

}  // namespace sm::io
