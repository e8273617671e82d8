// A march step through a pyramid, wedge or hexahedron with every local array indexed by
// constants: walk() calls it with the type as a literal, so that after inlining the loops over
// faces, triangles and vertices unroll and every table entry is a constant.
//
// Why: lavapipe keeps a dynamically indexed local array in memory and reads or writes it one lane
// at a time, while constant indices stay in vector registers. The table-driven step indexed its
// vertex and face arrays by loop counters and table entries and cost about 16 times a
// tetrahedron's step; unrolled, about 3 times (docs/BENCHMARKS.md: a hexahedral cube renders 5
// times faster, wedges and pyramids 3.5 times). The predicates, their operands and their order did
// not change (smMatchFace's count, the quad split, the triangle order), so walks and images are
// bit for bit those of the table-driven step.
#ifndef SM_ELEMENT_STEP_GLSL
#define SM_ELEMENT_STEP_GLSL

// The record of element (type, index), zero past its words; read as 64-bit words where records
// have an even number of words and so keep 8-byte alignment (all but plain pyramids): half the
// gathers.
void loadRecordOf(SceneRefs sc, uint type, uint index, out uint rec[8]) {
  uint words = recordWords(type);
  [[unroll]] for (uint i = 0u; i < 8u; ++i) rec[i] = 0u;
  if (words % 2u == 0u) {
    SmUint64s r = SmUint64s(sc.elements[type]);
    [[unroll]] for (uint i = 0u; i < 4u; ++i) {
      if (2u * i >= words) continue;
      uvec2 x = unpackUint2x32(r.v[index * (words / 2u) + i]);
      rec[2u * i] = x.x;
      rec[2u * i + 1u] = x.y;
    }
  } else {
    SmUints r = SmUints(sc.elements[type]);
    [[unroll]] for (uint i = 0u; i < 8u; ++i)
      if (i < words) rec[i] = r.v[index * words + i];
  }
}

// Reconstructs element (type, index) entered through face k[0..n-1] (its own outward order);
// returns the entry face, or -1 if the face does not belong to the element.
int decodeOf(SceneRefs sc, uint type, uint index, uint k[4], uint n, out uint v[8]) {
  uint rec[8];
  loadRecordOf(sc, type, index, rec);
  return kCompact ? smXorDecode(type, rec, k, n, v) : smPlainDecode(type, rec, k, n, v);
}

// Geometry of the element just entered: what the crossed face carried, the other vertices fetched
// and projected.
void geometryOf(RayFrame fr, SceneRefs sc, uint type, uint v[8], Walk w, FaceCarry c, bool carried,
                out ElementGeom g) {
  [[unroll]] for (uint i = 0u; i < 8u; ++i) {
    g.W[i] = vec3(0.0);
    g.P[i] = vec3(0.0);
    g.S[i] = 0.0;
    if (i >= SM_NUM_VERTS[type]) continue;
    uint id = v[i];
    vec4 rec = vertexRecord(sc, id);
    g.W[i] = rec.xyz;
    uint j = !carried ? 4u : id == w.k[0] ? 0u : id == w.k[1] ? 1u : id == w.k[2] ? 2u
           : (w.kn == 4u && id == w.k[3]) ? 3u : 4u;
    if (j < 4u) {
      g.P[i] = j == 0u ? c.P0 : j == 1u ? c.P1 : j == 2u ? c.P2 : c.P3;
      g.S[i] = j == 0u ? c.S0 : j == 1u ? c.S1 : j == 2u ? c.S2 : c.S3;
    } else {
      g.P[i] = projectVertex(fr, g.W[i]);
      g.S[i] = rec.w;
    }
  }
}

// Triangle k of face f (constants after unrolling): vertex ids, projected positions and scalars.
// A quad splits along the diagonal through its smallest vertex index (smQuadSplit: the shell and
// every element sharing the quad split it alike): diagonal a-c gives (a, b, c), (c, d, a);
// diagonal b-d gives (b, c, d), (d, a, b). A triangle is (a, b, c).
void triangleOf(uint type, uint v[8], ElementGeom g, uint f, uint k, out uint ia, out uint ib, out uint ic,
                out vec3 pa, out vec3 pb, out vec3 pc, out float sa, out float sb, out float sc) {
  uint la = smFaceVert(type, f, 0u), lb = smFaceVert(type, f, 1u);
  uint lc = smFaceVert(type, f, 2u), ld = smFaceVert(type, f, 3u);
  bool quad = smFaceSize(type, f) == 4u;
  uint m = min(min(v[la], v[lb]), min(v[lc], v[ld]));
  bool ac = !quad || m == v[la] || m == v[lc];
  ia = ac ? (k == 0u ? v[la] : v[lc]) : (k == 0u ? v[lb] : v[ld]);
  ib = ac ? (k == 0u ? v[lb] : v[ld]) : (k == 0u ? v[lc] : v[la]);
  ic = ac ? (k == 0u ? v[lc] : v[la]) : (k == 0u ? v[ld] : v[lb]);
  pa = ac ? (k == 0u ? g.P[la] : g.P[lc]) : (k == 0u ? g.P[lb] : g.P[ld]);
  pb = ac ? (k == 0u ? g.P[lb] : g.P[ld]) : (k == 0u ? g.P[lc] : g.P[la]);
  pc = ac ? (k == 0u ? g.P[lc] : g.P[la]) : (k == 0u ? g.P[ld] : g.P[lb]);
  sa = ac ? (k == 0u ? g.S[la] : g.S[lc]) : (k == 0u ? g.S[lb] : g.S[ld]);
  sb = ac ? (k == 0u ? g.S[lb] : g.S[ld]) : (k == 0u ? g.S[lc] : g.S[la]);
  sc = ac ? (k == 0u ? g.S[lc] : g.S[la]) : (k == 0u ? g.S[ld] : g.S[lb]);
}

// The face through which the ray leaves the element (side = +1) or, walking backward, came in
// (side = -1). Crossings are ordered as the perturbed ray meets them, (t, slopes) lexicographically:
// forward takes the first crossing strictly after the entry (tRef, slopeRef), backward the last
// strictly before it. Strict progress in that order is what keeps a walk through a vertex or the
// fold edge of a warped quad from cycling; in convex elements there is just one candidate anyway.
// Faces in table order, a quad's two triangles in triangleOf's order. Returns the face, or -1.
int crossingOf(uint type, uint v[8], ElementGeom g, int skipFace, int side, float tRef, vec2 slopeRef,
               out float t, out vec2 slope, out float s) {
  // Two phases, so that the costly code (exact signs, the crossing, the candidate rules) is
  // compiled once per type rather than once per triangle: first, unrolled, the triangles the ray
  // may cross on `side` (bit 2 f + k for triangle k of face f), dismissed only where edgeSign's
  // float test already decides every edge the other way; then, in order, each of those.
  uint maybe = 0u;
  [[unroll]] for (uint f = 0u; f < SM_MAX_FACES; ++f) {
    if (f >= SM_NUM_FACES[type]) continue;
    bool quad = smFaceSize(type, f) == 4u;
    // The side test excludes the triangle the ray came through; skipping the whole entry face is
    // an optimisation valid for triangles only: a warped quad can fold so that the ray leaves
    // through the other triangle of the quad it came in by.
    if (int(f) == skipFace && !quad) continue;
    [[unroll]] for (uint k = 0u; k < 2u; ++k) {
      if (k == 1u && !quad) continue;
      uint ia, ib, ic;
      vec3 pa, pb, pc;
      float sa, sb, sc;
      triangleOf(type, v, g, f, k, ia, ib, ic, pa, pb, pc, sa, sb, sc);
      precise float e0 = pa.x * pb.y - pa.y * pb.x;  // edgeSign's first test, edge by edge
      precise float e1 = pb.x * pc.y - pb.y * pc.x;
      precise float e2 = pc.x * pa.y - pc.y * pa.x;
      bool decided = (e0 > 0.0 || e0 < 0.0) && (e1 > 0.0 || e1 < 0.0) && (e2 > 0.0 || e2 < 0.0);
      bool crosses = side > 0 ? e0 > 0.0 && e1 > 0.0 && e2 > 0.0 : e0 < 0.0 && e1 < 0.0 && e2 < 0.0;
      if (!decided || crosses) maybe |= 1u << (2u * f + k);
    }
  }
  // Best candidate ahead of the entry (nearest first), and best one not ahead (least far behind):
  // a convex element has a single exit, whatever rounding says about its order.
  bool foundAhead = false, foundOther = false;
  int face = -1, faceOther = -1;
  float tOther = 0.0, sOther = 0.0;
  vec2 slopeOther = vec2(0.0);
  t = 0.0;
  slope = vec2(0.0);
  s = 0.0;
  SM_NO_UNROLL while (maybe != 0u) {
    uint i = uint(findLSB(maybe));
    maybe &= maybe - 1u;
    uint ia = 0u, ib = 0u, ic = 0u;
    vec3 pa = vec3(0.0), pb = vec3(0.0), pc = vec3(0.0);
    float sa = 0.0, sb = 0.0, sc = 0.0;
    // Triangle i's data by selects (a dynamic index into g would cost a load per lane).
    [[unroll]] for (uint f = 0u; f < SM_MAX_FACES; ++f) {
      [[unroll]] for (uint k = 0u; k < 2u; ++k) {
        if (f >= SM_NUM_FACES[type] || (k == 1u && smFaceSize(type, f) != 4u) || i != 2u * f + k) continue;
        triangleOf(type, v, g, f, k, ia, ib, ic, pa, pb, pc, sa, sb, sc);
      }
    }
    if (crossingSide(pa.xy, pb.xy, pc.xy) != side) continue;
    float tc;
    vec3 w;
    vec2 slopeC;
    triangleCrossing(ia, ib, ic, pa, pb, pc, tc, w, slopeC);
    float value = w.x * sa + w.y * sb + w.z * sc;
    bool ahead = side > 0 ? crossingBefore(tRef, slopeRef, tc, slopeC) : crossingBefore(tc, slopeC, tRef, slopeRef);
    if (ahead) {
      if (!foundAhead || (side > 0 ? crossingBefore(tc, slopeC, t, slope) : crossingBefore(t, slope, tc, slopeC))) {
        foundAhead = true;
        face = int(i >> 1u);
        t = tc;
        slope = slopeC;
        s = value;
      }
    } else if (!foundOther || (side > 0 ? crossingBefore(tOther, slopeOther, tc, slopeC)
                                        : crossingBefore(tc, slopeC, tOther, slopeOther))) {
      foundOther = true;
      faceOther = int(i >> 1u);
      tOther = tc;
      slopeOther = slopeC;
      sOther = value;
    }
  }
  if (foundAhead) return face;
  t = tOther;
  slope = slopeOther;
  s = sOther;
  return faceOther;
}

// Face f's n vertices (its outward order) with their geometry, for the carry; e3 and the fourth
// carry entry are zero on a triangle.
uint faceOf(uint type, uint v[8], ElementGeom g, int f, out uint e0, out uint e1, out uint e2, out uint e3,
            out FaceCarry ce) {
  e0 = e1 = e2 = e3 = 0u;
  ce = FaceCarry(vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), 0.0, 0.0, 0.0, 0.0);
  uint n = 0u;
  [[unroll]] for (uint ff = 0u; ff < SM_MAX_FACES; ++ff) {
    if (ff >= SM_NUM_FACES[type] || uint(f) != ff) continue;
    uint l0 = smFaceVert(type, ff, 0u), l1 = smFaceVert(type, ff, 1u);
    uint l2 = smFaceVert(type, ff, 2u), l3 = smFaceVert(type, ff, 3u);
    n = smFaceSize(type, ff);
    e0 = v[l0]; e1 = v[l1]; e2 = v[l2];
    ce.P0 = g.P[l0]; ce.P1 = g.P[l1]; ce.P2 = g.P[l2];
    ce.S0 = g.S[l0]; ce.S1 = g.S[l1]; ce.S2 = g.S[l2];
    if (n == 4u) {
      e3 = v[l3];
      ce.P3 = g.P[l3];
      ce.S3 = g.S[l3];
    }
  }
  return n;
}

// The parametric corner of local vertex i (VTK's order; a pyramid's apex at the middle of its top).
vec3 parametricCorner(uint type, uint i) {
  if (type == SM_WED) return vec3(float(i == 1u || i == 4u), float(i == 2u || i == 5u), float(i >= 3u));
  if (type == SM_PYR && i == 4u) return vec3(0.5, 0.5, 1.0);
  uint j = i & 3u;
  return vec3(float(j == 1u || j == 2u), float(j >= 2u), float(i >= 4u));
}

// Element-exact integration's first Newton guess for the point where the ray crosses face f: the
// ray's barycentric coordinates (the origin of the ray frame) in the projection of the triangle of
// the face's first three vertices, applied to their parametric corners; exact on a triangle and
// on a parallelogram. The element's centre where that triangle is degenerate in projection.
vec3 faceGuess(uint type, ElementGeom g, int f) {
  vec3 guess = parametricCenter(type);
  [[unroll]] for (uint ff = 0u; ff < SM_MAX_FACES; ++ff) {
    if (ff >= SM_NUM_FACES[type] || uint(f) != ff) continue;
    uint la = smFaceVert(type, ff, 0u), lb = smFaceVert(type, ff, 1u), lc = smFaceVert(type, ff, 2u);
    vec2 A = g.P[la].xy, ab = g.P[lb].xy - A, ac = g.P[lc].xy - A;
    float d = ab.x * ac.y - ab.y * ac.x;
    float wb = (ac.x * A.y - ac.y * A.x) / d, wc = (ab.y * A.x - ab.x * A.y) / d;
    vec3 ca = parametricCorner(type, la);
    vec3 q = ca + wb * (parametricCorner(type, lb) - ca) + wc * (parametricCorner(type, lc) - ca);
    if (abs(d) > 0.0 && !any(isnan(q)) && !any(isinf(q))) guess = clamp(q, vec3(0.0), vec3(1.0));
  }
  return guess;
}

// One step through element (type, index) entered by walk w: the exit face (or -1 when the walk is
// lost), its crossing, neighbour and vertices; g receives the element's geometry, and in
// element-exact mode, walking forward, guess the parametric point of the entry (faceGuess).
int stepOf(RayFrame fr, SceneRefs sc, uint type, uint index, Walk w, FaceCarry c, bool carried, int side,
           out ElementGeom g, out float t, out vec2 slope, out float s, out uint ref, out uint n, out uint e0,
           out uint e1, out uint e2, out uint e3, out FaceCarry ce, inout vec3 guess) {
  t = 0.0;
  slope = vec2(0.0);
  s = 0.0;
  e0 = e1 = e2 = e3 = 0u;
  ce = FaceCarry(vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), 0.0, 0.0, 0.0, 0.0);
  uint v[8];
  ref = SM_NO_NEIGHBOR;
  n = 0u;
  int entry = decodeOf(sc, type, index, w.k, w.kn, v);
  if (entry < 0) return -1;
  geometryOf(fr, sc, type, v, w, c, carried, g);
  if (kElementExact && side > 0) guess = faceGuess(type, g, entry);
  int f = crossingOf(type, v, g, entry, side, w.tIn, w.slopeIn, t, slope, s);
  if (f < 0) return -1;
  ref = neighborOf(sc, type, index, uint(f));
  n = faceOf(type, v, g, f, e0, e1, e2, e3, ce);
  return f;
}

#endif
