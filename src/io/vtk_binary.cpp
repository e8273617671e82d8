#include "io/vtk_binary.h"

#include <zlib.h>

#include <algorithm>
#include <cstring>

#include "common/check.h"
#include "common/error.h"
#include "common/parallel.h"
#include "io_core/text_scan.h"

namespace sm::io {
namespace {

uint64_t readHeaderValue(const uint8_t* p, const BinaryFormat& f) {
  return f.header64 ? loadAs<uint64_t>(p, f.swap) : loadAs<uint32_t>(p, f.swap);
}

// Refuses an array whose header gives a size other than the one expected of it.
void checkSize(uint64_t declared, uint64_t expected, Length length, const std::string& source,
               const std::string& what) {
  if (declared == expected || (length == Length::AtLeast && declared > expected)) return;
  throw FileError(source, what, ": the array holds ", declared, " bytes, expected ",
                  length == Length::AtLeast ? "at least " : "", expected);
}

Payload readUncompressed(PayloadSource& src, const BinaryFormat& f, uint64_t expected,
                         const std::string& source, const std::string& what, Length length) {
  const uint64_t hs = f.header64 ? 8 : 4;
  ByteBuffer headerScratch;
  const uint8_t* h = src.take(hs, headerScratch);
  if (!h)
    throw FileError(source, what, ": ", src.whyShort("the data ends before the array's header"));
  const uint64_t declared = readHeaderValue(h, f);
  checkSize(declared, expected, length, source, what);
  if (declared > src.maxRemaining())
    throw FileError(source, what, ": needs ", declared, " bytes but the data ends after ",
                    src.maxRemaining());
  Payload p;
  p.bytes = declared;
  p.data = src.take(declared, p.storage);
  if (!p.data)
    throw FileError(source, what, ": ", src.whyShort("the data ends before the array does"));
  return p;
}

// A compressed array's block table, checked against the data present.
struct BlockTable {
  uint64_t blocks = 0, blockSize = 0, lastSize = 0;
  uint64_t total = 0;                // uncompressed bytes
  std::vector<uint64_t> compOffset;  // block b's compressed bytes: [compOffset[b], [b + 1])

  uint64_t size(uint64_t b) const { return b + 1 == blocks && lastSize ? lastSize : blockSize; }
};

// The block count, block size and last block size, and the total they give.
BlockTable readBlockSizes(PayloadSource& src, const BinaryFormat& f, const std::string& source,
                          const std::string& what) {
  const uint64_t hs = f.header64 ? 8 : 4;
  ByteBuffer scratch;
  const uint8_t* h = src.take(3 * hs, scratch);
  if (!h)
    throw FileError(source, what, ": ",
                    src.whyShort("the data ends before the compression header"));
  BlockTable t;
  t.blocks = readHeaderValue(h, f);
  t.blockSize = readHeaderValue(h + hs, f);
  t.lastSize = readHeaderValue(h + 2 * hs, f);
  if (t.blocks > src.maxRemaining() / hs)
    throw FileError(source, what, ": the compression header claims ", t.blocks,
                    " blocks, more than the data can hold");
  if (t.lastSize > t.blockSize)
    throw FileError(source, what, ": the last compressed block (", t.lastSize,
                    " bytes) is larger than the block size (", t.blockSize, ")");
  if (t.blocks > 0) {
    if (t.blocks - 1 > (UINT64_MAX - t.blockSize) / std::max<uint64_t>(t.blockSize, 1))
      throw FileError(source, what, ": the compression header claims an impossible size");
    t.total = (t.blocks - 1) * t.blockSize + (t.lastSize ? t.lastSize : t.blockSize);
  }
  return t;
}

// The compressed size of each block, which must all lie within the data and could hold the total.
void readCompressedSizes(PayloadSource& src, const BinaryFormat& f, BlockTable& t,
                         const std::string& source, const std::string& what) {
  const uint64_t hs = f.header64 ? 8 : 4;
  ByteBuffer scratch;
  const uint8_t* s = src.take(t.blocks * hs, scratch);
  if (!s)
    throw FileError(source, what, ": ",
                    src.whyShort("the data ends inside the compression header"));
  t.compOffset.assign(t.blocks + 1, 0);
  for (uint64_t b = 0; b < t.blocks; ++b) {
    uint64_t c = readHeaderValue(s + b * hs, f);
    if (c > src.maxRemaining() || t.compOffset[b] + c > src.maxRemaining())
      throw FileError(source, what, ": compressed block ", b, " runs past the end of the data");
    t.compOffset[b + 1] = t.compOffset[b] + c;
  }
  const uint64_t compTotal = t.compOffset[t.blocks];
  if (t.total / maxExpansion(f.compressor) > compTotal + 64 * t.blocks)
    throw FileError(source, what, ": claims ", t.total, " bytes from ", compTotal,
                    " compressed bytes, more than ", compressorName(f.compressor), " can produce");
}

Payload readCompressed(PayloadSource& src, const BinaryFormat& f, uint64_t expected,
                       const std::string& source, const std::string& what, Length length) {
  BlockTable t = readBlockSizes(src, f, source, what);
  checkSize(t.total, expected, length, source, what);
  readCompressedSizes(src, f, t, source, what);
  ByteBuffer compScratch;
  const uint8_t* comp = src.take(t.compOffset[t.blocks], compScratch);
  if (!comp)
    throw FileError(source, what, ": ", src.whyShort("the data ends inside the compressed blocks"));
  auto corrupt = [&](uint64_t b, const std::string& why) {
    return FileError(source, what, ": compressed block ", b, " is corrupt (", why, ")");
  };
  for (uint64_t b = 0; b < t.blocks; ++b) {
    const std::string why = checkRecordedSize(f.compressor, comp + t.compOffset[b],
                                              t.compOffset[b + 1] - t.compOffset[b], t.size(b));
    if (!why.empty()) throw corrupt(b, why);
  }
  Payload p;
  p.bytes = t.total;
  p.storage = ByteBuffer::allocate(t.total);
  p.data = p.storage.data();
  uint8_t* out = p.storage.data();
  parallelFor(
      static_cast<int64_t>(t.blocks),
      [&](int64_t b0, int64_t b1) {
        for (uint64_t b = uint64_t(b0); b < uint64_t(b1); ++b) {
          throwIfStopped(f.stop, source);
          const std::string why =
              decodeBlock(f.compressor, comp + t.compOffset[b],
                          t.compOffset[b + 1] - t.compOffset[b], out + b * t.blockSize, t.size(b));
          if (!why.empty()) throw corrupt(b, why);
        }
      },
      f.threads, 4);
  return p;
}

}  // namespace

PayloadSource PayloadSource::raw(std::span<const uint8_t> bytes, size_t pos) {
  return PayloadSource(bytes, std::min(pos, bytes.size()), {}, false);
}

PayloadSource PayloadSource::base64(std::string_view text, size_t pos) {
  return PayloadSource({}, std::min(pos, text.size()), text, true);
}

const uint8_t* PayloadSource::take(uint64_t n, ByteBuffer& scratch) {
  if (!isBase64_) {
    if (n > raw_.size() - pos_) return nullptr;
    const uint8_t* p = raw_.data() + pos_;
    pos_ += n;
    return p;
  }
  if (n > b64_.maxRemaining()) return nullptr;
  scratch = ByteBuffer::allocate(std::max<uint64_t>(n, 1));
  return b64_.read(scratch.data(), n) ? scratch.data() : nullptr;
}

std::string PayloadSource::whyShort(const std::string& ends) const {
  const size_t bad = isBase64_ ? b64_.badCharacter() : std::string_view::npos;
  if (bad == std::string_view::npos) return ends;
  const char c = b64_.characterAt(bad);
  return concat(c == '=' ? "padding '=' out of place"
                         : concat("'", printable(std::string(1, c)), "', not base64,"),
                " at character ", bad, " of its base64 text");
}

uint64_t PayloadSource::maxRemaining() const {
  return isBase64_ ? b64_.maxRemaining() : raw_.size() - pos_;
}

Payload readPayload(PayloadSource& src, const BinaryFormat& format, uint64_t expectedBytes,
                    const std::string& source, const std::string& what, Length length) {
  throwIfStopped(format.stop, source);
  return format.compressor == Compressor::None
             ? readUncompressed(src, format, expectedBytes, source, what, length)
             : readCompressed(src, format, expectedBytes, source, what, length);
}

std::vector<uint8_t> compressBlocks(uint64_t bytes, uint64_t blockSize, int level, unsigned threads,
                                    const std::function<void(uint64_t, uint64_t, uint8_t*)>& fill) {
  const uint64_t nBlocks = (bytes + blockSize - 1) / blockSize;
  const uint64_t last = bytes % blockSize;
  std::vector<std::vector<uint8_t>> blocks(nBlocks);
  parallelFor(
      static_cast<int64_t>(nBlocks),
      [&](int64_t b0, int64_t b1) {
        // No larger than the data: a piece's small arrays would otherwise each zero a whole
        // block (megabytes of page faults per array when writing thousands of pieces).
        std::vector<uint8_t> raw(std::min(blockSize, bytes));
        for (int64_t b = b0; b < b1; ++b) {
          uint64_t n = std::min(blockSize, bytes - uint64_t(b) * blockSize);
          fill(uint64_t(b) * blockSize, n, raw.data());
          uLongf cap = compressBound(n);
          blocks[b].resize(cap);
          int rc = compress2(blocks[b].data(), &cap, raw.data(), n, level);
          SM_CHECK_EQ(rc, Z_OK);
          blocks[b].resize(cap);
        }
      },
      threads, 2);
  std::vector<uint64_t> header = {nBlocks, blockSize, last};
  uint64_t total = (3 + nBlocks) * 8;
  for (const auto& b : blocks) {
    header.push_back(b.size());
    total += b.size();
  }
  std::vector<uint8_t> out(total);
  for (size_t i = 0; i < header.size(); ++i) {
    uint64_t v = std::endian::native == std::endian::little ? header[i] : byteSwap(header[i]);
    std::memcpy(out.data() + i * 8, &v, 8);
  }
  uint64_t pos = header.size() * 8;
  for (const auto& b : blocks) {
    std::memcpy(out.data() + pos, b.data(), b.size());
    pos += b.size();
  }
  return out;
}

}  // namespace sm::io
