// The one cell and face table (docs/DESIGN.md invariant 1), shared by C++ and GLSL.
//
// Element types and their vertex order are VTK's. Faces are listed so that, for a positively
// oriented element, every face is wound counter-clockwise seen from outside (right-hand normal
// points out). Elements are reoriented at load so that this holds for every element we keep.
// Quads are split into two triangles along the diagonal through their smallest global vertex
// index (smQuadSplit), so both elements sharing a quad, and the shell, split it identically.
// Tables laid out by hand, one row per cell type or face: clang-format would reflow them.
// clang-format off
#ifndef SM_CELL_TABLES_H
#define SM_CELL_TABLES_H

#include "glsl_cpp.h"

SM_BEGIN_NAMESPACE

SM_CONST uint SM_TET = 0u;
SM_CONST uint SM_PYR = 1u;
SM_CONST uint SM_WED = 2u;
SM_CONST uint SM_HEX = 3u;
SM_CONST uint SM_NUM_TYPES = 4u;
SM_CONST uint SM_MAX_VERTS = 8u;
SM_CONST uint SM_MAX_FACES = 6u;
SM_CONST uint SM_NO_NEIGHBOR = 0xFFFFFFFFu;

// VTK cell type codes of the four linear volume cells.
SM_CONST uint SM_VTK_TETRA = 10u;
SM_CONST uint SM_VTK_HEXAHEDRON = 12u;
SM_CONST uint SM_VTK_WEDGE = 13u;
SM_CONST uint SM_VTK_PYRAMID = 14u;

// Per-type counts: vertices, faces, 32-bit words per element plain and XOR-compacted.
#define SM_NUM_VERTS_DATA 4u, 5u, 6u, 8u
#define SM_NUM_FACES_DATA 4u, 5u, 5u, 6u
#define SM_PLAIN_WORDS_DATA 4u, 5u, 6u, 8u
#define SM_COMPACT_WORDS_DATA 1u, 4u, 4u, 8u

// Face sizes, indexed [type * 6 + face]; 0 marks no such face.
#define SM_FACE_SIZE_DATA                                                   \
  3u, 3u, 3u, 3u, 0u, 0u, /* tet */                                         \
  4u, 3u, 3u, 3u, 3u, 0u, /* pyramid */                                     \
  3u, 3u, 4u, 4u, 4u, 0u, /* wedge */                                       \
  4u, 4u, 4u, 4u, 4u, 4u /* hexahedron */

// Face vertices (local indices), indexed [(type * 6 + face) * 4 + k]. Triangles repeat their
// first vertex in slot 3 so that the array stays rectangular.
#define SM_FACE_VERT_DATA                                                                      \
  0u, 1u, 3u, 0u, 1u, 2u, 3u, 1u, 2u, 0u, 3u, 2u, 0u, 2u, 1u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u, \
  0u, 3u, 2u, 1u, 0u, 1u, 4u, 0u, 1u, 2u, 4u, 1u, 2u, 3u, 4u, 2u, 3u, 0u, 4u, 3u, 0u, 0u, 0u, 0u, \
  0u, 1u, 2u, 0u, 3u, 5u, 4u, 3u, 0u, 3u, 4u, 1u, 1u, 4u, 5u, 2u, 2u, 5u, 3u, 0u, 0u, 0u, 0u, 0u, \
  0u, 4u, 7u, 3u, 1u, 2u, 6u, 5u, 0u, 1u, 5u, 4u, 3u, 7u, 6u, 2u, 0u, 3u, 2u, 1u, 4u, 5u, 6u, 7u

#ifdef __cplusplus
SM_CONST uint SM_NUM_VERTS[4] = {SM_NUM_VERTS_DATA};
SM_CONST uint SM_NUM_FACES[4] = {SM_NUM_FACES_DATA};
SM_CONST uint SM_PLAIN_WORDS[4] = {SM_PLAIN_WORDS_DATA};
SM_CONST uint SM_COMPACT_WORDS[4] = {SM_COMPACT_WORDS_DATA};
SM_CONST uint SM_FACE_SIZE[24] = {SM_FACE_SIZE_DATA};
SM_CONST uint SM_FACE_VERT[96] = {SM_FACE_VERT_DATA};
#else
const uint SM_NUM_VERTS[4] = uint[4](SM_NUM_VERTS_DATA);
const uint SM_NUM_FACES[4] = uint[4](SM_NUM_FACES_DATA);
const uint SM_PLAIN_WORDS[4] = uint[4](SM_PLAIN_WORDS_DATA);
const uint SM_COMPACT_WORDS[4] = uint[4](SM_COMPACT_WORDS_DATA);
const uint SM_FACE_SIZE[24] = uint[24](SM_FACE_SIZE_DATA);
const uint SM_FACE_VERT[96] = uint[96](SM_FACE_VERT_DATA);
#endif

SM_FN uint smFaceSize(uint type, uint face) { return SM_FACE_SIZE[type * 6u + face]; }
SM_FN uint smFaceVert(uint type, uint face, uint k) { return SM_FACE_VERT[(type * 6u + face) * 4u + k]; }

// Element reference as stored in shell triangles and connectivity: index << 2 | type.
SM_FN uint smElemRef(uint index, uint type) { return (index << 2u) | type; }
SM_FN uint smRefType(uint ref) { return ref & 3u; }
SM_FN uint smRefIndex(uint ref) { return ref >> 2u; }
SM_CONST uint SM_MAX_ELEMS_PER_TYPE = 0x40000000u;  // 2^30: what an element reference can address

// Splits quad (a, b, c, d), given in cyclic order, into two triangles of the same winding along the
// diagonal through its smallest vertex index. Each triangle is three consecutive vertices of the
// cycle; `other` is the quad vertex that the triangle leaves out, so (t0, t1, t2, other) is again
// the quad's cycle. Triangle 0 is (t[0..2]), triangle 1 is (t[3..5]).
SM_FN void smQuadSplit(uint a, uint b, uint c, uint d, SM_OUT_ARR(uint, t, 6), SM_OUT_ARR(uint, other, 2)) {
  uint m = a;
  if (b < m) m = b;
  if (c < m) m = c;
  if (d < m) m = d;
  if (m == a || m == c) {  // diagonal a-c
    t[0] = a; t[1] = b; t[2] = c; other[0] = d;
    t[3] = c; t[4] = d; t[5] = a; other[1] = b;
  } else {  // diagonal b-d
    t[0] = b; t[1] = c; t[2] = d; other[0] = a;
    t[3] = d; t[4] = a; t[5] = b; other[1] = c;
  }
}

SM_END_NAMESPACE

#endif
// clang-format on
