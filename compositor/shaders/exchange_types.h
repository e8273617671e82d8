// Push constants of the compositor's exchange and compositing shaders, shared by C++ and GLSL
// (GLSL includes this after enabling GL_EXT_shader_explicit_arithmetic_types_int64). 64-bit fields
// first, so that C++ and GLSL scalar layout agree.
#ifndef DC_EXCHANGE_TYPES_H
#define DC_EXCHANGE_TYPES_H

#include "fragment_types.h"

#ifdef __cplusplus
namespace sm::comp {
#endif

// Which rank composites which pixels. The exchange works on positions: rank r composites the
// contiguous positions [begin(r), end(r)) (compositor/exchange_plan.h), so that each destination's
// share of a send buffer is contiguous. Ranges: positions are pixels, rank r composites pixels
// [floor(r P / R), floor((r + 1) P / R)) (the paper's layout). Interleaved: rank r composites the
// pixels p = r (mod R), the j-th of them (p = j R + r) at position begin(r) + j, where the first
// P mod R ranks hold one pixel more (begin(r) = r floor(P / R) + min(r, P mod R)); whatever part
// of the image the data covers, every rank gets its share of it (IceT interlaces images for the
// same reason).
DC_CONST uint DC_OWNERSHIP_RANGES = 0u;
DC_CONST uint DC_OWNERSHIP_INTERLEAVED = 1u;

// Division by the rank count without a divide: a vector division is a loop of eight scalar ones
// on lavapipe, which made the passes that map pixels to positions cost as much as the rest of step
// 1. floor(n / d) = (t + ((n - t) >> 1)) >> (l - 1), t = mulhi(n, m), for every 32-bit n, with
// l = ceil(log2 d) and m = floor(2^32 (2^l - d) / d) + 1 (Granlund and Montgomery 1994; Hacker's
// Delight 10-8). d >= 2; dcDivisionMagic computes (m, l - 1) on the host.
struct DcDivisor {
  uint magic;
  uint shift;
};

DC_FN uint dcMulHi(uint a, uint b) {
#ifdef __cplusplus
  return uint((uint64_t(a) * uint64_t(b)) >> 32u);
#else
  uint hi, lo;
  umulExtended(a, b, hi, lo);
  return hi;
#endif
}

DC_FN uint dcDivide(uint n, DcDivisor d) {
  uint t = dcMulHi(n, d.magic);
  return (t + ((n - t) >> 1u)) >> d.shift;
}

// Interleaved: the position of pixel p, with base = floor(P / R) and extra = P mod R given.
DC_FN uint dcInterleavedPosition(uint p, uint ranks, DcDivisor byRanks, uint base, uint extra) {
  uint j = dcDivide(p, byRanks), r = p - j * ranks;
  return r * base + (r < extra ? r : extra) + j;
}

// composite_local.comp (one rank): lists start at offsets[p] (two-pass) or p * fixedK (offsets ==
// 0); image holds one premultiplied vec4 per pixel.
struct DcLocalPush {
  uint64_t fragments;
  uint64_t counts;
  uint64_t offsets;
  uint64_t image;
  uint pixels;
  uint fixedK;
};

// list_stats.comp: result[0] = longest list, [1] = non-empty pixels, [2] = fragments.
struct DcStatsPush {
  uint64_t counts;
  uint64_t result;
  uint pixels;
};

// compact.comp / flatten.comp: a pixel's list starts at srcOffsets[p] (two-pass) or p * fixedK
// (srcOffsets == 0). compact copies pixel p's list to dst at dstOffsets[q], q its position (p
// itself, or with interleaved != 0 dcInterleavedPosition with ranks, base, extra); flatten
// composites it into one fragment dst[p] and writes dstCounts[p] = 0 or 1.
struct DcCompactPush {
  uint64_t src;
  uint64_t counts;
  uint64_t srcOffsets;
  uint64_t dst;
  uint64_t dstOffsets;  // compact only
  uint64_t dstCounts;   // flatten only
  uint pixels;
  uint fixedK;
  uint interleaved;  // compact only, as the next four
  uint ranks;
  DcDivisor byRanks;
  uint base;
  uint extra;
};

// permute_counts.comp: dst[dcInterleavedPosition(p)] = src[p], the counts in position order.
struct DcPermutePush {
  uint64_t src;
  uint64_t dst;
  uint pixels;
  uint ranks;
  DcDivisor byRanks;
  uint base;
  uint extra;
};

// encode_counts.comp: segments holds (first position, first word) of each destination, ranks + 1
// pairs; counts are in position order; one invocation packs one output word.
struct DcEncodePush {
  uint64_t counts;
  uint64_t segments;
  uint64_t words;
  uint ranks;
  uint totalWords;
  uint bits;
};

// decode_counts.comp: counters of source s start at word s * wordsPerSource.
struct DcDecodePush {
  uint64_t words;
  uint64_t counts;
  uint perSource;
  uint sources;
  uint wordsPerSource;
  uint bits;
};

// composite_deep.comp: list (s, j) has counts[s * pixels + j] fragments at offsets[s * pixels + j].
struct DcDeepPush {
  uint64_t fragments;
  uint64_t counts;
  uint64_t offsets;
  uint64_t image;
  uint pixels;
  uint ranks;
};

// write_lists.comp: host fragments (five floats, pixel p's at rawOffsets[p], rawCounts[p] of them)
// written through the device interface. countOnly: write capacities[p] = rawCounts[p] (the
// two-pass counting pass); otherwise write the lists (offsets: two-pass list starts, or 0).
struct DcWritePush {
  uint64_t raw;
  uint64_t rawOffsets;
  uint64_t rawCounts;
  uint64_t capacities;
  uint64_t offsets;
  uint64_t counts;
  uint64_t fragments;
  uint pixels;
  uint fixedK;
  uint countOnly;
};

#ifdef __cplusplus
static_assert(sizeof(DcLocalPush) == 40);
static_assert(sizeof(DcWritePush) == 72);
static_assert(sizeof(DcStatsPush) == 24);
static_assert(sizeof(DcCompactPush) == 80);
static_assert(sizeof(DcPermutePush) == 40);
static_assert(sizeof(DcEncodePush) == 40);
static_assert(sizeof(DcDecodePush) == 32);
static_assert(sizeof(DcDeepPush) == 40);
}  // namespace sm::comp
#endif

#endif
