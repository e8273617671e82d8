#include "io/block_codec.h"

#include <lz4.h>
#include <lzma.h>
#include <zlib.h>

#include <algorithm>
#include <climits>

#include "common/error.h"

namespace sm::io {
namespace {

// VTK's presets go up to 9, whose 64 MiB dictionary needs about 65 MiB to decode; an .xz header
// asking for more is damaged, and must not make us allocate it.
constexpr uint64_t kLzmaMemLimit = uint64_t(128) << 20;

std::string zlibDecode(const uint8_t* in, uint64_t n, uint8_t* out, uint64_t want) {
  uLongf got = want;
  const int rc = uncompress(out, &got, in, n);
  if (rc == Z_OK && got == want) return "";
  return concat("zlib: ", rc == Z_OK ? "wrong size" : zError(rc));
}

std::string lz4Decode(const uint8_t* in, uint64_t n, uint8_t* out, uint64_t want) {
  if (n > uint64_t(INT_MAX) || want > uint64_t(INT_MAX))
    return concat("lz4: ", std::max(n, want), " bytes, more than an LZ4 block can hold");
  const int got =
      LZ4_decompress_safe(reinterpret_cast<const char*>(in), reinterpret_cast<char*>(out),
                          static_cast<int>(n), static_cast<int>(want));
  if (got == static_cast<int>(want)) return "";
  // A negative count is also what a block longer than the room given yields.
  return got < 0 ? concat("lz4: malformed, or more than the ", want, " bytes the header says")
                 : "lz4: wrong size";
}

std::string lzmaReason(lzma_ret rc) {
  switch (rc) {
    case LZMA_FORMAT_ERROR:
      return "not an .xz stream";
    case LZMA_OPTIONS_ERROR:
      return "unsupported options";
    case LZMA_DATA_ERROR:
      return "data error";
    case LZMA_BUF_ERROR:
      return "wrong size";
    case LZMA_MEMLIMIT_ERROR:
      return concat("needs more than ", kLzmaMemLimit >> 20, " MiB");
    case LZMA_MEM_ERROR:
      return "out of memory";
    default:
      return concat("error ", int(rc));
  }
}

std::string lzmaDecode(const uint8_t* in, uint64_t n, uint8_t* out, uint64_t want) {
  uint64_t memLimit = kLzmaMemLimit;
  size_t inPos = 0, outPos = 0;
  const lzma_ret rc =
      lzma_stream_buffer_decode(&memLimit, 0, nullptr, in, &inPos, n, out, &outPos, want);
  if (rc == LZMA_OK && outPos == want) return "";
  return concat("lzma: ", rc == LZMA_OK ? "wrong size" : lzmaReason(rc));
}

// The stream's index (at its end, found from the footer) records what it decodes to, under a
// CRC32: reading it first keeps a damaged block table from allocating what it merely claims.
std::string lzmaCheckRecordedSize(const uint8_t* in, uint64_t n, uint64_t want) {
  if (n < 2 * LZMA_STREAM_HEADER_SIZE) return "lzma: shorter than an .xz stream";
  lzma_stream_flags footer;
  lzma_ret rc = lzma_stream_footer_decode(&footer, in + n - LZMA_STREAM_HEADER_SIZE);
  if (rc != LZMA_OK) return concat("lzma: stream footer: ", lzmaReason(rc));
  const uint64_t indexEnd = n - LZMA_STREAM_HEADER_SIZE;
  if (footer.backward_size > indexEnd - LZMA_STREAM_HEADER_SIZE)
    return "lzma: its index lies outside the stream";
  lzma_index* index = nullptr;
  uint64_t memLimit = kLzmaMemLimit;
  size_t pos = 0;
  rc = lzma_index_buffer_decode(&index, &memLimit, nullptr, in + indexEnd - footer.backward_size,
                                &pos, footer.backward_size);
  if (rc != LZMA_OK) return concat("lzma: stream index: ", lzmaReason(rc));
  const uint64_t recorded = lzma_index_uncompressed_size(index);
  lzma_index_end(index, nullptr);
  if (recorded == want) return "";
  return concat("lzma: wrong size (its index records ", recorded, " bytes)");
}

}  // namespace

const char* compressorName(Compressor c) {
  switch (c) {
    case Compressor::ZLib:
      return "zlib";
    case Compressor::LZ4:
      return "lz4";
    case Compressor::LZMA:
      return "lzma";
    case Compressor::None:
      break;
  }
  return "none";
}

uint64_t maxExpansion(Compressor c) {
  switch (c) {
    case Compressor::ZLib:
      return 1032;  // deflate cannot expand data by more than about 1032:1
    case Compressor::LZ4:
      return 256;  // each length byte of 255 adds at most 255 bytes
    // Long runs approach 7000:1 (a 273-byte match costs about 0.3 bits at the coder's most
    // confident probabilities); xz 5.4 gives 6851:1 on 256 MiB of zeros.
    case Compressor::LZMA:
      return 8192;
    case Compressor::None:
      break;
  }
  return 1;
}

std::string checkRecordedSize(Compressor c, const uint8_t* in, uint64_t n, uint64_t want) {
  return c == Compressor::LZMA ? lzmaCheckRecordedSize(in, n, want) : "";
}

std::string decodeBlock(Compressor c, const uint8_t* in, uint64_t n, uint8_t* out, uint64_t want) {
  switch (c) {
    case Compressor::ZLib:
      return zlibDecode(in, n, out, want);
    case Compressor::LZ4:
      return lz4Decode(in, n, out, want);
    case Compressor::LZMA:
      return lzmaDecode(in, n, out, want);
    case Compressor::None:
      break;
  }
  return "not compressed";
}

}  // namespace sm::io
