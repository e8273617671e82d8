// The bytes of one input file, in memory. Files are memory-mapped copy-on-write, so that parsers
// may work in place (pugixml writes terminators into its buffer) without a copy and without
// touching the file; in-memory inputs (fuzzers, tests) are copied into an owned buffer.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace sm::io {

class FileBytes {
 public:
  // Throws sm::FileError naming the file when it cannot be opened or mapped.
  static FileBytes open(const std::string& path);
  static FileBytes copyOf(std::span<const uint8_t> bytes);

  FileBytes() = default;
  FileBytes(FileBytes&& other) noexcept;
  FileBytes& operator=(FileBytes&& other) noexcept;
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;
  ~FileBytes();

  uint8_t* data() { return data_; }
  const uint8_t* data() const { return data_; }
  size_t size() const { return size_; }
  std::span<uint8_t> span() { return {data_, size_}; }
  std::span<const uint8_t> span() const { return {data_, size_}; }

 private:
  void release();
  uint8_t* data_ = nullptr;
  size_t size_ = 0;
  bool mapped_ = false;
  std::unique_ptr<uint8_t[]> owned_;
};

}  // namespace sm::io
