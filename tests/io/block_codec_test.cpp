// Compressed block tables with each compressor VTK's XML writer offers, built here the way that
// writer builds them (vtkZLibDataCompressor, vtkLZ4DataCompressor, vtkLZMADataCompressor), then
// damaged: a damaged block must be one FileError naming the block, whatever the compressor.
#include <gtest/gtest.h>
#include <lz4.h>
#include <lzma.h>
#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "common/error.h"
#include "io/vtk_binary.h"

namespace sm::io {
namespace {

std::vector<uint8_t> compressBlock(Compressor c, const uint8_t* in, size_t n) {
  std::vector<uint8_t> out;
  if (c == Compressor::ZLib) {
    uLongf size = compressBound(n);
    out.resize(size);
    EXPECT_EQ(compress2(out.data(), &size, in, n, 6), Z_OK);
    out.resize(size);
  } else if (c == Compressor::LZ4) {
    out.resize(size_t(LZ4_compressBound(int(n))));
    const int size =
        LZ4_compress_default(reinterpret_cast<const char*>(in), reinterpret_cast<char*>(out.data()),
                             int(n), int(out.size()));
    EXPECT_GT(size, 0);
    out.resize(size_t(size));
  } else {
    out.resize(lzma_stream_buffer_bound(n));
    size_t size = 0;
    EXPECT_EQ(
        lzma_easy_buffer_encode(5, LZMA_CHECK_CRC32, nullptr, in, n, out.data(), &size, out.size()),
        LZMA_OK);
    out.resize(size);
  }
  return out;
}

void putHeader(std::vector<uint8_t>& enc, size_t slot, uint64_t value) {
  std::memcpy(enc.data() + slot * 8, &value, 8);  // the tests run little-endian
}

// VTK's layout with a UInt64 header: block count, block size, last block size (0 when full),
// each block's compressed size, then the blocks.
std::vector<uint8_t> vtkBlocks(Compressor c, const std::vector<uint8_t>& raw, uint64_t blockSize) {
  const uint64_t blocks = (raw.size() + blockSize - 1) / blockSize;
  std::vector<uint8_t> enc((3 + blocks) * 8);
  putHeader(enc, 0, blocks);
  putHeader(enc, 1, blockSize);
  putHeader(enc, 2, raw.size() % blockSize);
  for (uint64_t b = 0; b < blocks; ++b) {
    const uint64_t n = std::min<uint64_t>(blockSize, raw.size() - b * blockSize);
    const std::vector<uint8_t> block = compressBlock(c, raw.data() + b * blockSize, n);
    putHeader(enc, 3 + b, block.size());
    enc.insert(enc.end(), block.begin(), block.end());
  }
  return enc;
}

// Compressible, but not one run: LZ4 then has literals, matches and length bytes to damage.
std::vector<uint8_t> sample(size_t n) {
  std::vector<uint8_t> raw(n);
  for (size_t i = 0; i < n; ++i) raw[i] = uint8_t(i / 3 % 17 + (i % 5 == 0 ? 100 : 0));
  return raw;
}

// Where block b's compressed bytes start in vtkBlocks' output.
size_t blockStart(const std::vector<uint8_t>& enc, uint64_t b) {
  uint64_t blocks = 0, pos = 0;
  std::memcpy(&blocks, enc.data(), 8);
  pos = (3 + blocks) * 8;
  for (uint64_t k = 0; k < b; ++k) {
    uint64_t c = 0;
    std::memcpy(&c, enc.data() + (3 + k) * 8, 8);
    pos += c;
  }
  return pos;
}

class CompressedBlocks : public ::testing::TestWithParam<Compressor> {
 protected:
  BinaryFormat format() const {
    BinaryFormat f;
    f.header64 = true;
    f.compressor = GetParam();
    return f;
  }
  // The message readPayload gives for enc, expected to hold `bytes`.
  std::string errorOf(const std::vector<uint8_t>& enc, uint64_t bytes) const {
    PayloadSource src = PayloadSource::raw(enc, 0);
    try {
      readPayload(src, format(), bytes, "t.vtu", "array 'x'");
    } catch (const FileError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      return e.what();
    }
    ADD_FAILURE() << "no FileError";
    return "";
  }
  std::string corruptBlock(uint64_t b) const {
    return std::string("t.vtu: array 'x': compressed block ") + std::to_string(b) +
           " is corrupt (" + compressorName(GetParam()) + ": ";
  }
};

TEST_P(CompressedBlocks, RoundTripWithPartialAndFullLastBlocks) {
  for (size_t bytes : {size_t(0), size_t(1), size_t(4096), size_t(5000)}) {
    SCOPED_TRACE(bytes);
    const std::vector<uint8_t> raw = sample(bytes);
    const std::vector<uint8_t> enc = vtkBlocks(GetParam(), raw, 1024);
    PayloadSource src = PayloadSource::raw(enc, 0);
    Payload p = readPayload(src, format(), bytes, "t.vtu", "array");
    ASSERT_EQ(p.bytes, bytes);
    EXPECT_TRUE(bytes == 0 || std::memcmp(p.data, raw.data(), bytes) == 0);
  }
}

// The first byte of a block is structure in every format (zlib's header, LZ4's first token, the
// .xz magic); a middle byte is caught by zlib's and xz's checksums (LZ4 has none).
TEST_P(CompressedBlocks, ADamagedByteIsAFileErrorNamingTheBlock) {
  const std::vector<uint8_t> raw = sample(5000);
  const std::vector<uint8_t> enc = vtkBlocks(GetParam(), raw, 1024);
  // (position, the block it lies in); LZ4 has no checksum, so a byte inside its literals may
  // decode to other values without an error, as in VTK: only block starts for it.
  std::vector<std::pair<size_t, uint64_t>> at = {{blockStart(enc, 2), 2}, {blockStart(enc, 4), 4}};
  if (GetParam() != Compressor::LZ4)
    at.push_back({(blockStart(enc, 3) + blockStart(enc, 4)) / 2, 3});
  for (const auto& [pos, block] : at) {
    SCOPED_TRACE(pos);
    std::vector<uint8_t> bad = enc;
    bad[pos] ^= 0x55;
    const std::string msg = errorOf(bad, raw.size());
    EXPECT_EQ(msg.rfind(corruptBlock(block), 0), 0u) << msg;
    EXPECT_NE(msg.find(std::string(" is corrupt (") + compressorName(GetParam()) + ": "),
              std::string::npos)
        << msg;
  }
}

// A header whose block sizes add up to what the array should hold, but not to what a block
// decodes to: the last block (904 bytes) declared shorter or longer.
TEST_P(CompressedBlocks, ABlockOfAnotherSizeThanTheHeaderSaysIsAFileError) {
  const std::vector<uint8_t> raw = sample(5000);
  for (uint64_t last : {uint64_t(900), uint64_t(1000)}) {
    SCOPED_TRACE(last);
    std::vector<uint8_t> enc = vtkBlocks(GetParam(), raw, 1024);
    putHeader(enc, 2, last);
    const std::string msg = errorOf(enc, 4 * 1024 + last);
    EXPECT_EQ(msg.rfind(corruptBlock(4), 0), 0u) << msg;
  }
  // Block size and last size changed together, the total kept: every block is off.
  std::vector<uint8_t> enc = vtkBlocks(GetParam(), raw, 1024);
  putHeader(enc, 1, 1025);
  putHeader(enc, 2, 900);
  const std::string msg = errorOf(enc, raw.size());
  EXPECT_NE(msg.find(" is corrupt ("), std::string::npos) << msg;
}

TEST_P(CompressedBlocks, TruncatedOrShortenedBlocksAreFileErrors) {
  const std::vector<uint8_t> raw = sample(5000);
  const std::vector<uint8_t> enc = vtkBlocks(GetParam(), raw, 1024);
  for (size_t cut = 0; cut < enc.size(); cut += 7) {
    const std::vector<uint8_t> part(enc.begin(), enc.begin() + long(cut));
    EXPECT_EQ(errorOf(part, raw.size()).rfind("t.vtu: array 'x': ", 0), 0u) << cut;
  }
  // The last block one byte short, its compressed size in the header too.
  std::vector<uint8_t> shorter(enc.begin(), enc.end() - 1);
  putHeader(shorter, 3 + 4, enc.size() - 1 - blockStart(enc, 4));
  const std::string msg = errorOf(shorter, raw.size());
  EXPECT_EQ(msg.rfind(corruptBlock(4), 0), 0u) << msg;
}

INSTANTIATE_TEST_SUITE_P(VtkCompressors, CompressedBlocks,
                         ::testing::Values(Compressor::ZLib, Compressor::LZ4, Compressor::LZMA),
                         [](const auto& info) { return std::string(compressorName(info.param)); });

}  // namespace
}  // namespace sm::io
