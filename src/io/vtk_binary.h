// Binary array data in VTK XML files. Each array is a header followed by its bytes: uncompressed,
// the header is the byte count; compressed, it is the block table (number of blocks, block size,
// size of the last block, compressed size of each block) and the blocks follow, each compressed
// on its own. Header integers are UInt32 or UInt64 (header_type) in the file's byte order. The
// bytes sit raw in <AppendedData>, or base64-encoded (inline, or appended with encoding="base64").
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "io/base64.h"
#include "io/block_codec.h"
#include "io_core/numeric_array.h"
#include "io_core/read_stop.h"

namespace sm::io {

struct BinaryFormat {
  bool header64 = false;  // header_type="UInt64"
  bool swap = false;      // byte_order is not the host's
  Compressor compressor = Compressor::None;
  unsigned threads = 0;  // decompressing blocks (0: all cores)
  StopRequested stop;    // asked before each compressed block (ReadOptions::stopRequested)
};

// Sequential reader over raw bytes or base64 text.
class PayloadSource {
 public:
  static PayloadSource raw(std::span<const uint8_t> bytes, size_t pos);
  static PayloadSource base64(std::string_view text, size_t pos);

  // The next n bytes: a view into the input (raw) or decoded into scratch (base64). Null when
  // the data ends first.
  const uint8_t* take(uint64_t n, ByteBuffer& scratch);
  // Upper bound on the bytes left (exact for raw data).
  uint64_t maxRemaining() const;
  // Why take returned null, for messages: `ends` ("the data ends ..."), unless a character that
  // is not base64 stopped the decoding, which is named instead.
  std::string whyShort(const std::string& ends) const;

 private:
  PayloadSource(std::span<const uint8_t> raw, size_t pos, std::string_view text, bool isBase64)
      : raw_(raw), pos_(pos), b64_(text, pos), isBase64_(isBase64) {}
  std::span<const uint8_t> raw_;
  size_t pos_;
  Base64Reader b64_;
  bool isBase64_;
};

// One array's bytes: a view into the input when raw and uncompressed, else decoded into storage.
struct Payload {
  const uint8_t* data = nullptr;
  ByteBuffer storage;
  uint64_t bytes = 0;  // as its header says
};

// How many bytes an array may hold: exactly those expected, or those and more (VTK reads an array
// by its own length; one listing entries nothing refers to is valid there).
enum class Length { Exact, AtLeast };

// Reads one array (header and data, decompressing blocks in parallel) that must hold
// expectedBytes (or, Length::AtLeast, no fewer). Every size in the header is checked against the
// data actually present before anything is allocated; errors are sm::FileError(source, what, ...).
Payload readPayload(PayloadSource& src, const BinaryFormat& format, uint64_t expectedBytes,
                    const std::string& source, const std::string& what,
                    Length length = Length::Exact);

// Writer side: `bytes` bytes, produced block by block by fill(offset, n, dst), as zlib blocks
// of blockSize bytes with a UInt64 little-endian block table in front (VTK's layout).
std::vector<uint8_t> compressBlocks(uint64_t bytes, uint64_t blockSize, int level, unsigned threads,
                                    const std::function<void(uint64_t, uint64_t, uint8_t*)>& fill);

}  // namespace sm::io
