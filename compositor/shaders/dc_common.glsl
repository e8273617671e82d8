// Includes and buffer types the compositor's own shaders share.
#ifndef DC_COMMON_GLSL
#define DC_COMMON_GLSL

#extension GL_GOOGLE_include_directive : require
#include "fragment_list.glsl"
#include "exchange_types.h"
#include "dispatch_grid.glsl"

layout(buffer_reference, scalar) buffer DcUint3 { uint v[3]; };

// A pixel's list in the renderer's storage: two-pass lists start at offsets[p], fixed-length ones
// at p * K.
uint dcListBase(uint64_t offsets, uint fixedK, uint p) {
  return offsets != 0ul ? DcUints(offsets).v[p] : p * fixedK;
}

#endif
