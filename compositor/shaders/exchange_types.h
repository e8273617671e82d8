// Push constants of the compositor's exchange and compositing shaders, shared by C++ and GLSL
// (GLSL includes this after enabling GL_EXT_shader_explicit_arithmetic_types_int64). 64-bit fields
// first, so that C++ and GLSL scalar layout agree.
#ifndef DC_EXCHANGE_TYPES_H
#define DC_EXCHANGE_TYPES_H

#include "fragment_types.h"

#ifdef __cplusplus
namespace sm::comp {
#endif

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
// (srcOffsets == 0). compact copies it to dst at dstOffsets[p]; flatten composites it into one
// fragment dst[p] and writes dstCounts[p] = 0 or 1.
struct DcCompactPush {
  uint64_t src;
  uint64_t counts;
  uint64_t srcOffsets;
  uint64_t dst;
  uint64_t dstOffsets;  // compact only
  uint64_t dstCounts;   // flatten only
  uint pixels;
  uint fixedK;
};

// encode_counts.comp: segments holds (first pixel, first word) of each destination, ranks + 1
// pairs; one invocation packs one output word.
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
static_assert(sizeof(DcCompactPush) == 56);
static_assert(sizeof(DcEncodePush) == 40);
static_assert(sizeof(DcDecodePush) == 32);
static_assert(sizeof(DcDeepPush) == 40);
}  // namespace sm::comp
#endif

#endif
