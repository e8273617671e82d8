// The bytes of one input file, in memory. Files are memory-mapped read-only (binary data is used
// in place, no copy); a parser that must write into its buffer (pugixml's in-place parsing) asks
// for writableData(), which turns the mapping copy-on-write, so only the pages it writes are
// copied and the file is never touched. In-memory inputs (fuzzers, tests) are copied.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace sm::io {

class FileBytes {
 public:
  // Throws sm::FileError naming the file when it cannot be opened or mapped. Every page is mapped
  // up front (for a file read whole).
  static FileBytes open(const std::string& path);
  // The same, pages mapped as they are first touched: for a read of one array among many (a
  // time step's).
  static FileBytes openLazily(const std::string& path);
  // At most the first `bytes` bytes of a regular file (a header), with open's checks.
  static std::string readPrefix(const std::string& path, size_t bytes);
  static FileBytes copyOf(std::span<const uint8_t> bytes);

  FileBytes() = default;
  FileBytes(FileBytes&& other) noexcept;
  FileBytes& operator=(FileBytes&& other) noexcept;
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;
  ~FileBytes();

  const uint8_t* data() const { return data_; }
  size_t size() const { return size_; }
  std::span<const uint8_t> span() const { return {data_, size_}; }
  // The same bytes, writable (copy-on-write for mapped files).
  uint8_t* writableData();

 private:
  static FileBytes map(const std::string& path, bool populate);
  void release();
  uint8_t* data_ = nullptr;
  size_t size_ = 0;
  bool mapped_ = false;
  bool writable_ = false;
  std::unique_ptr<uint8_t[]> owned_;
};

}  // namespace sm::io
