// The compressors of VTK XML binary arrays, one block at a time. VTK compresses every block on its
// own: zlib as a zlib stream, LZ4 as one raw LZ4 block (no frame), LZMA as a complete .xz stream
// (lzma_easy_buffer_encode). The block table around them is vtk_binary.cpp's.
#pragma once

#include <cstdint>
#include <string>

namespace sm::io {

enum class Compressor { None, ZLib, LZ4, LZMA };

// The name messages give the compressor ("zlib", "lz4", "lzma").
const char* compressorName(Compressor c);

// The most a compressor can expand its data: a block table claiming more than this many bytes per
// compressed byte is corrupt, and is refused before anything that large is allocated.
uint64_t maxExpansion(Compressor c);

// Checks, before the output is allocated, the uncompressed size a block records of itself under
// a checksum, where its format records one (an .xz stream's index). Returns "" when it is `want`
// or there is no record, else why not, as decodeBlock does.
std::string checkRecordedSize(Compressor c, const uint8_t* in, uint64_t n, uint64_t want);

// Decodes the n bytes at `in` into exactly `want` bytes at `out`. Returns "" on success, else why
// not ("lz4: wrong size"), for a message that calls the block corrupt.
std::string decodeBlock(Compressor c, const uint8_t* in, uint64_t n, uint8_t* out, uint64_t want);

}  // namespace sm::io
