// Device interface of the deep compositor (the paper's "Fragment List Management"): a renderer
// writes a pixel's fragments through these functions and the compositor does the rest.
//
// One invocation owns one pixel and writes its fragments front to back (segments of one ray never
// overlap, so entry distance order is visibility order). Modes (specialization constant):
//   DC_TWO_PASS   the pixel's list lives at [base, base + capacity) found by a counting pass and a
//                 prefix sum: exact, never overflows.
//   DC_FIXED_DROP fixed K slots per pixel: once full, later (farther) fragments are dropped.
//   DC_FIXED_MERGE fixed K slots: once full, the lowest-opacity fragment among the K + 1 is composited
//                 onto its front neighbour (keeping that neighbour's depth), freeing a slot.
// Encodings: five floats (premultiplied rgba + depth) or rgba8 + float depth. Zero-opacity
// fragments are dropped.
#ifndef DC_FRAGMENT_LIST_GLSL
#define DC_FRAGMENT_LIST_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "fragment_types.h"

layout(constant_id = 100) const uint kDcMode = DC_TWO_PASS;
layout(constant_id = 101) const uint kDcEncoding = DC_ENCODING_FLOAT;

layout(buffer_reference, scalar) buffer DcFloatFragments { DcFragment v[]; };
layout(buffer_reference, scalar) buffer DcPackedFragments { DcPackedFragment v[]; };
layout(buffer_reference, scalar) buffer DcUints { uint v[]; };

struct DcListWriter {
  uint64_t fragments;
  uint base;
  uint capacity;
  uint count;
  uint overflow;
};

DcListWriter dcBegin(uint64_t fragments, uint base, uint capacity) {
  DcListWriter w;
  w.fragments = fragments;
  w.base = base;
  w.capacity = capacity;
  w.count = 0u;
  w.overflow = 0u;
  return w;
}

void dcStore(uint64_t fragments, uint slot, DcFragment f) {
  if (kDcEncoding == DC_ENCODING_FLOAT) {
    DcFloatFragments(fragments).v[slot] = f;
  } else {
    DcPackedFragments(fragments).v[slot] = dcPack(f);
  }
}

DcFragment dcLoad(uint64_t fragments, uint slot) {
  if (kDcEncoding == DC_ENCODING_FLOAT) return DcFloatFragments(fragments).v[slot];
  return dcUnpack(DcPackedFragments(fragments).v[slot]);
}

// Merges the lowest-opacity fragment of the full list plus `f` (the K + 1 sequence [stored..., f])
// into its front neighbour, or into its back neighbour when it is the frontmost, keeping the front
// one's depth; then appends f unless f itself was merged.
void dcMergeInto(inout DcListWriter w, DcFragment f) {
  uint n = w.capacity;  // the list is full: n stored + f
  uint lowest = n;      // index n stands for f
  float lowestA = f.color.a;
  for (uint i = 0u; i < n; ++i) {
    float a = dcLoad(w.fragments, w.base + i).color.a;
    if (a < lowestA) { lowestA = a; lowest = i; }
  }
  uint front = lowest == 0u ? 0u : lowest - 1u;
  uint back = front + 1u;  // <= n; n is f (K = 1 or f lowest)
  DcFragment b = back == n ? f : dcLoad(w.fragments, w.base + back);
  dcStore(w.fragments, w.base + front, dcOver(dcLoad(w.fragments, w.base + front), b));
  if (back == n) return;
  for (uint i = back; i + 1u < n; ++i) dcStore(w.fragments, w.base + i, dcLoad(w.fragments, w.base + i + 1u));
  dcStore(w.fragments, w.base + n - 1u, f);
}

void dcWrite(inout DcListWriter w, DcFragment f) {
  if (!(f.color.a > 0.0)) return;  // also drops NaN opacity
  if (w.count < w.capacity) {
    dcStore(w.fragments, w.base + w.count, f);
    w.count += 1u;
    return;
  }
  w.overflow += 1u;
  if (kDcMode == DC_FIXED_MERGE && w.capacity > 0u) dcMergeInto(w, f);
}

void dcEnd(DcListWriter w, uint64_t counts, uint pixel) { DcUints(counts).v[pixel] = w.count; }

#endif
