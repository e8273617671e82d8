// XOR compaction of element vertex indices (the paper's section "XOR-compaction"), shared by the
// preparation (C++ encode, round-trip tests) and the marcher (GLSL decode).
//
// Records, in 32-bit words, vertices in VTK order:
//   tet  (4 B): v0^v1^v2^v3
//   pyr (16 B): v0^v2, v1, v3, v4          (dx, diag[2], top)
//   wed (16 B): v2^v3, v1^v5, v0, v4       (dx[2], diag[2])
//   hex (32 B): v0..v7 (no compaction)
//
// Decoding needs the entry face: its vertices k[0..n-1] in the element's own outward cyclic order
// (the reverse of the order in which the previous element, or the shell, lists it as outward), with
// n = 4 for quads. Pyramids, wedges and hexahedra decode to their exact VTK order, so connectivity
// slots are VTK face numbers. Tetrahedra decode to (k0, k2, k1, d): a positively oriented order in
// which face 3 is the entry face; their connectivity slot for a face is the rank (0..3) of the
// opposite vertex's index among the tet's four (smTetSlot), which does not depend on vertex order.
// Laid out by hand, one record per cell type a line: clang-format would reflow them.
// clang-format off
#ifndef SM_XOR_CODEC_H
#define SM_XOR_CODEC_H

#include "cell_tables.h"

SM_BEGIN_NAMESPACE

// k[i] for i < 4 by selects, and the position of x among k[0..n-1]: a per-lane index into a
// local array costs a load and a store per lane on lavapipe, a select one vector instruction.
SM_FN uint smPick4(SM_IN_ARR(uint, k, 4), uint i) {
  return i == 0u ? k[0] : i == 1u ? k[1] : i == 2u ? k[2] : k[3];
}

SM_FN int smFindIdx(SM_IN_ARR(uint, k, 4), uint n, uint x) {
  return (n > 0u && k[0] == x) ? 0 : (n > 1u && k[1] == x) ? 1 : (n > 2u && k[2] == x) ? 2
       : (n > 3u && k[3] == x) ? 3 : -1;
}

// Connectivity slot of the tet face opposite vertex x: how many of the tet's vertices are smaller.
SM_FN uint smTetSlot(SM_IN_ARR(uint, v, 8), uint x) {
  uint r = 0u;
  SM_NO_UNROLL for (uint i = 0u; i < 4u; ++i) {
    if (v[i] < x) r += 1u;
  }
  return r;
}

SM_FN void smXorEncode(uint type, SM_IN_ARR(uint, v, 8), SM_OUT_ARR(uint, rec, 8)) {
  SM_NO_UNROLL for (uint i = 0u; i < 8u; ++i) rec[i] = 0u;
  if (type == SM_TET) {
    rec[0] = v[0] ^ v[1] ^ v[2] ^ v[3];
  } else if (type == SM_PYR) {
    rec[0] = v[0] ^ v[2]; rec[1] = v[1]; rec[2] = v[3]; rec[3] = v[4];
  } else if (type == SM_WED) {
    rec[0] = v[2] ^ v[3]; rec[1] = v[1] ^ v[5]; rec[2] = v[0]; rec[3] = v[4];
  } else {
    SM_NO_UNROLL for (uint i = 0u; i < 8u; ++i) rec[i] = v[i];
  }
}

// Face of `type` that holds all n known vertices (n = 3 may be three vertices of a quad); -1 if
// none. Two faces of a valid element share at most an edge, so the answer is unique. Unrolled over
// the largest type with guards, so that for a literal type every index is a constant.
SM_FN int smMatchFace(uint type, SM_IN_ARR(uint, v, 8), SM_IN_ARR(uint, k, 4), uint n) {
  int face = -1;
  SM_UNROLL for (uint f = 0u; f < SM_MAX_FACES; ++f) {
    if (f >= SM_NUM_FACES[type]) continue;
    uint fs = smFaceSize(type, f);
    uint found = 0u;
    SM_UNROLL for (uint j = 0u; j < 4u; ++j) {
      if (j < fs && smFindIdx(k, n, v[smFaceVert(type, f, j)]) >= 0) found += 1u;
    }
    if (face < 0 && fs >= n && found == n) face = int(f);
  }
  return face;
}

SM_FN int smDecodeTet(uint fourth, SM_IN_ARR(uint, k, 4), SM_OUT_ARR(uint, v, 8)) {
  v[0] = k[0]; v[1] = k[2]; v[2] = k[1]; v[3] = fourth;
  SM_NO_UNROLL for (uint i = 4u; i < 8u; ++i) v[i] = 0u;
  return 3;
}

SM_FN int smXorDecodePyr(SM_IN_ARR(uint, rec, 8), SM_IN_ARR(uint, k, 4), uint n, SM_OUT_ARR(uint, v, 8)) {
  uint dx = rec[0];
  v[1] = rec[1]; v[3] = rec[2]; v[4] = rec[3];
  v[5] = 0u; v[6] = 0u; v[7] = 0u;
  int it = smFindIdx(k, n, v[4]);
  if (it >= 0) {  // triangle face (v_a, v_b, v4): after the apex come the face's base vertices
    if (n != 3u) return -1;
    uint x = smPick4(k, (uint(it) + 1u) % 3u), y = smPick4(k, (uint(it) + 2u) % 3u);
    if (x == v[1]) { v[2] = y; v[0] = dx ^ y; return 2; }
    if (y == v[1]) { v[0] = x; v[2] = dx ^ x; return 1; }
    if (x == v[3]) { v[0] = y; v[2] = dx ^ y; return 4; }
    if (y == v[3]) { v[2] = x; v[0] = dx ^ x; return 3; }
    return -1;
  }
  // Base quad, outward cycle (v0, v3, v2, v1): v3 is followed by v2 and v1 by v0. Any three
  // consecutive vertices of the cycle contain one of those two pairs.
  uint m = (n == 4u) ? 4u : 2u;  // successor pairs available (cyclic for 4, a path for 3)
  SM_NO_UNROLL for (uint i = 0u; i < m; ++i) {
    uint a = smPick4(k, i), b = smPick4(k, (i + 1u) % n);
    if (a == v[3]) { v[2] = b; v[0] = dx ^ b; return 0; }
    if (a == v[1]) { v[0] = b; v[2] = dx ^ b; return 0; }
  }
  return -1;
}

SM_FN int smXorDecodeWed(SM_IN_ARR(uint, rec, 8), SM_IN_ARR(uint, k, 4), uint n, SM_OUT_ARR(uint, v, 8)) {
  uint dx0 = rec[0], dx1 = rec[1];
  v[0] = rec[2]; v[4] = rec[3];
  v[6] = 0u; v[7] = 0u;
  int i0 = smFindIdx(k, n, v[0]);
  int i4 = smFindIdx(k, n, v[4]);
  if (n == 3u) {
    if (i0 >= 0 && i4 < 0) {  // face 0 (v0, v1, v2)
      v[1] = smPick4(k, (uint(i0) + 1u) % 3u); v[2] = smPick4(k, (uint(i0) + 2u) % 3u);
      v[3] = dx0 ^ v[2]; v[5] = dx1 ^ v[1];
      return 0;
    }
    if (i4 >= 0 && i0 < 0) {  // face 1 (v3, v5, v4): after v4 come v3, v5
      v[3] = smPick4(k, (uint(i4) + 1u) % 3u); v[5] = smPick4(k, (uint(i4) + 2u) % 3u);
      v[2] = dx0 ^ v[3]; v[1] = dx1 ^ v[5];
      return 1;
    }
    return -1;
  }
  if (n != 4u) return -1;
  if (i0 >= 0 && i4 >= 0) {  // face 2 (v0, v3, v4, v1)
    v[3] = smPick4(k, (uint(i0) + 1u) % 4u); v[1] = smPick4(k, (uint(i0) + 3u) % 4u);
    if (smPick4(k, (uint(i0) + 2u) % 4u) != v[4]) return -1;
    v[2] = dx0 ^ v[3]; v[5] = dx1 ^ v[1];
    return 2;
  }
  if (i4 >= 0) {  // face 3 (v1, v4, v5, v2): after v4 come v5, v2, v1
    v[5] = smPick4(k, (uint(i4) + 1u) % 4u); v[2] = smPick4(k, (uint(i4) + 2u) % 4u);
    v[1] = smPick4(k, (uint(i4) + 3u) % 4u);
    v[3] = dx0 ^ v[2];
    return 3;
  }
  if (i0 >= 0) {  // face 4 (v2, v5, v3, v0): after v0 come v2, v5, v3
    v[2] = smPick4(k, (uint(i0) + 1u) % 4u); v[5] = smPick4(k, (uint(i0) + 2u) % 4u);
    v[3] = smPick4(k, (uint(i0) + 3u) % 4u);
    v[1] = dx1 ^ v[5];
    return 4;
  }
  return -1;
}

// Reconstructs element vertices from an XOR-compacted record and the entry face. Returns the entry
// face number, or -1 when the known vertices cannot be an entry face of this record.
SM_FN int smXorDecode(uint type, SM_IN_ARR(uint, rec, 8), SM_IN_ARR(uint, k, 4), uint n, SM_OUT_ARR(uint, v, 8)) {
  if (type == SM_TET) {
    if (n != 3u) return -1;
    return smDecodeTet(rec[0] ^ k[0] ^ k[1] ^ k[2], k, v);
  }
  if (type == SM_PYR) return smXorDecodePyr(rec, k, n, v);
  if (type == SM_WED) return smXorDecodeWed(rec, k, n, v);
  SM_UNROLL for (uint i = 0u; i < 8u; ++i) v[i] = rec[i];
  return smMatchFace(type, v, k, n);
}

// Same contract for plain records (vertices in VTK order); tets are reordered as smXorDecode does.
SM_FN int smPlainDecode(uint type, SM_IN_ARR(uint, rec, 8), SM_IN_ARR(uint, k, 4), uint n, SM_OUT_ARR(uint, v, 8)) {
  if (type == SM_TET) {
    if (n != 3u) return -1;
    uint fourth = 0u;
    uint missing = 0u;
    SM_NO_UNROLL for (uint i = 0u; i < 4u; ++i) {
      if (smFindIdx(k, 3u, rec[i]) < 0) { fourth = rec[i]; missing += 1u; }
    }
    if (missing != 1u) return -1;
    return smDecodeTet(fourth, k, v);
  }
  SM_UNROLL for (uint i = 0u; i < 8u; ++i) v[i] = rec[i];
  return smMatchFace(type, v, k, n);
}

SM_END_NAMESPACE

#endif
// clang-format on
