// Element marching (the paper's "Per-Segment Volume Integration"): from the element behind a
// segment's entry, walk element to element through the connectivity, finding each exit face with
// the exact crossing predicates (ray_frame.glsl), and integrate the samples of the global grid
// t_k = k dt that fall inside each element. Every walk has a step bound (invariant 6).
#ifndef SM_MARCH_GLSL
#define SM_MARCH_GLSL

#include "ray_frame.glsl"
#include "scene_access.glsl"
#include "interpolate.glsl"

// The walk's state between elements: it enters element `next` through face k[0..kn-1] (listed in
// that element's own outward order) at ray distance tIn, where the crossing's slopes are slopeIn
// (for ties) and the scalar is sIn.
struct Walk {
  uint next;  // element reference (index << 2 | type)
  uint k[4];
  uint kn;
  float tIn;
  vec2 slopeIn;
  float sIn;
};

// Geometry of a pyramid, wedge or hexahedron. Tetrahedra keep theirs in plain variables: lavapipe
// compiles a dynamically indexed local array to per-lane scalar loads and masked stores, while
// constant indices (and selects) stay in vector registers, so the dominant element type never
// touches these arrays.
struct ElementGeom {
  vec3 P[8];  // projected vertices (xy in the ray frame, z = foot distance)
  vec3 W[8];  // rebased world positions (for Newton)
  float S[8]; // vertex scalars
};

// Projected position and scalar of the vertices of the face just crossed, in the order of Walk.k:
// the next element takes them over instead of fetching and projecting them again (projection is
// deterministic per vertex, so this is exact). A tetrahedron then fetches one vertex per step.
struct FaceCarry {
  vec3 P0, P1, P2, P3;
  float S0, S1, S2, S3;
};

#include "transfer.glsl"

void loadVertex(RayFrame fr, SceneRefs sc, uint id, out vec3 P, out float S) {
  vec4 r = vertexRecord(sc, id);
  P = projectVertex(fr, r.xyz);
  S = r.w;
}

// Geometry of the pyramid, wedge or hexahedron just entered: what the crossed face carried, the
// other vertices fetched.
void elementGeometry(RayFrame fr, SceneRefs sc, uint type, uint v[8], Walk w, FaceCarry c, bool carried,
                     out ElementGeom g) {
  SM_NO_UNROLL for (uint i = 0u; i < SM_NUM_VERTS[type]; ++i) {
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

// Local vertex indices of the (up to two) triangles of face f, split by the shared rule.
uint faceTriangles(uint type, uint v[8], uint f, out uint tri[6]) {
  uint a = smFaceVert(type, f, 0u), b = smFaceVert(type, f, 1u), c = smFaceVert(type, f, 2u);
  if (smFaceSize(type, f) == 3u) {
    tri[0] = a; tri[1] = b; tri[2] = c;
    tri[3] = a; tri[4] = b; tri[5] = c;
    return 1u;
  }
  uint d = smFaceVert(type, f, 3u);
  uint m = min(min(v[a], v[b]), min(v[c], v[d]));
  if (m == v[a] || m == v[c]) {
    tri[0] = a; tri[1] = b; tri[2] = c; tri[3] = c; tri[4] = d; tri[5] = a;
  } else {
    tri[0] = b; tri[1] = c; tri[2] = d; tri[3] = d; tri[4] = a; tri[5] = b;
  }
  return 2u;
}

// The face through which the ray leaves the element (side = +1) or, walking backward, came in
// (side = -1). Crossings are ordered as the perturbed ray meets them, (t, slopes) lexicographically:
// forward takes the first crossing strictly after the entry (tRef, slopeRef), backward the last
// strictly before it. Strict progress in that order is what keeps a walk through a vertex or the
// fold edge of a warped quad from cycling; in convex elements there is just one candidate anyway.
// Tetrahedron entered through face 3 (decoded tets always are), vertices p0..p3: its other faces
// share the edges of the entry face, whose signs the entry already fixed, so the exit is decided by
// the signs of the three edges to the fourth vertex alone (the paper's "at most 2 tests"). These are
// the very edge signs the general test would compute, so the decision is the same. Returns -1 when
// an edge is degenerate in projection and the general test must decide.
int tetExitFace(vec2 p0, vec2 p1, vec2 p2, vec2 p3, int side) {
  int e0 = edgeSign(p0, p3);
  int e1 = edgeSign(p1, p3);
  int e2 = edgeSign(p2, p3);
  if (e0 == 0 || e1 == 0 || e2 == 0) return -1;
  if (e1 == side && e0 == -side) return 0;  // face 0 (0, 1, 3)
  if (e2 == side && e1 == -side) return 1;  // face 1 (1, 2, 3)
  if (e0 == side && e2 == -side) return 2;  // face 2 (2, 0, 3)
  return -1;
}

// The general test for tetrahedra: the first of faces 0, 1, 2 (face 0 is (0, 1, 3), face f is
// (f, f + 1 mod 3, 3)) that the ray crosses on `side` (a convex element with planar faces has just
// one). One loop, so that the shader holds one copy of the three crossing tests.
int tetCrossedFace(vec2 p0, vec2 p1, vec2 p2, vec2 p3, int side) {
  SM_NO_UNROLL for (int f = 0; f < 3; ++f) {
    vec2 a = f == 0 ? p0 : f == 1 ? p1 : p2;
    vec2 b = f == 0 ? p1 : f == 1 ? p2 : p0;
    if (crossingSide(a, b, p3) == side) return f;
  }
  return -1;
}

// The same search for pyramids, wedges and hexahedra, whose faces may be quads split in two.
bool findCrossing(uint type, uint v[8], ElementGeom g, int skipFace, int side, float tRef, vec2 slopeRef,
                  out int face, out float t, out vec2 slope, out float s) {
  // Best candidate ahead of the entry (nearest first), and best one not ahead (least far behind):
  // a convex element has a single exit, whatever rounding says about its order.
  bool foundAhead = false, foundOther = false;
  int faceOther = -1;
  float tOther = 0.0, sOther = 0.0;
  vec2 slopeOther = vec2(0.0);
  face = -1;
  t = 0.0;
  slope = vec2(0.0);
  s = 0.0;
  SM_NO_UNROLL for (uint f = 0u; f < SM_NUM_FACES[type]; ++f) {
    // The side test excludes the triangle the ray came through; skipping the whole entry face is
    // an optimisation valid for triangles only: a warped quad can fold so that the ray leaves
    // through the other triangle of the quad it came in by.
    if (int(f) == skipFace && smFaceSize(type, f) == 3u) continue;
    uint tri[6];
    uint nt = faceTriangles(type, v, f, tri);
    SM_NO_UNROLL for (uint k = 0u; k < nt; ++k) {
      uint a = tri[3u * k], b = tri[3u * k + 1u], c = tri[3u * k + 2u];
      if (crossingSide(g.P[a].xy, g.P[b].xy, g.P[c].xy) != side) continue;
      float tc;
      vec3 w;
      vec2 sc;
      triangleCrossing(v[a], v[b], v[c], g.P[a], g.P[b], g.P[c], tc, w, sc);
      float value = w.x * g.S[a] + w.y * g.S[b] + w.z * g.S[c];
      bool ahead = side > 0 ? crossingBefore(tRef, slopeRef, tc, sc) : crossingBefore(tc, sc, tRef, slopeRef);
      if (ahead) {
        if (!foundAhead || (side > 0 ? crossingBefore(tc, sc, t, slope) : crossingBefore(t, slope, tc, sc))) {
          foundAhead = true;
          face = int(f);
          t = tc;
          slope = sc;
          s = value;
        }
      } else if (!foundOther ||
                 (side > 0 ? crossingBefore(tOther, slopeOther, tc, sc) : crossingBefore(tc, sc, tOther, slopeOther))) {
        foundOther = true;
        faceOther = int(f);
        tOther = tc;
        slopeOther = sc;
        sOther = value;
      }
    }
  }
  if (foundAhead) return true;
  face = faceOther;
  t = tOther;
  slope = slopeOther;
  s = sOther;
  return foundOther;
}

struct MarchResult {
  vec4 color;     // premultiplied, front to back
  float tEnd;     // forward: where the walk left the rank's volume
  uint status;    // 0 ok, 1 lost, 2 step limit
  uint steps;
  uint samples;
};

const uint MARCH_OK = 0u;
const uint MARCH_LOST = 1u;
const uint MARCH_STEP_LIMIT = 2u;

// The element walk. Forward (side +1): from walk `w`, integrate the samples from tLimit on until
// the walk leaves the volume. Backward (side -1): walk against the ray, without sampling, to the
// element that holds tLimit (or to the shell face where the volume begins if that comes first);
// `w` then holds that element entered through that crossing, ready for a forward walk.
// One function for both directions so that the shader holds one copy of the crossing search,
// decoding and geometry code (Mesa inlines every call site; compile time grows with size). Each
// step takes one of two paths, tetrahedra and the rest, which meet again at the exit crossing.
MarchResult walk(RayFrame fr, FrameParams fp, inout Walk w, int side, float tLimit) {
  MarchResult r;
  r.color = vec4(0.0);
  r.tEnd = w.tIn;
  r.status = MARCH_STEP_LIMIT;
  r.steps = 0u;
  r.samples = 0u;
  SceneRefs sc = fp.scene;
  ElementGeom g;
  FaceCarry c = FaceCarry(vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), 0.0, 0.0, 0.0, 0.0);
  bool carried = false;  // nothing to carry into the first element
  uint kNext = kNoSample;
  SM_NO_UNROLL for (uint step = 0u; step < fp.maxElementSteps; ++step) {
    r.steps += 1u;
    uint type = specialisedType(smRefType(w.next)), index = smRefIndex(w.next);
    // Per path: the exit crossing (face f at t, slope, scalar s), the neighbour behind it, the
    // face's vertices e0..e3 (n of them) in this element's outward order with their geometry, and
    // the gradient of a tetrahedron (shading only).
    int f;
    float t, s;
    vec2 slope;
    uint ref, n = 3u;
    uint e0, e1, e2, e3 = 0u;
    FaceCarry ce;
    vec3 tetGrad = vec3(0.0);
    if (type == SM_TET) {
      // Decoded as (k0, k2, k1, fourth), entered through face 3 (xor_codec.h); the entry face's
      // vertices come from the carry.
      if (w.kn != 3u) {
        r.status = MARCH_LOST;
        return r;
      }
      uint v0 = w.k[0], v1 = w.k[2], v2 = w.k[1], v3;
      SmUints rec = SmUints(sc.elements[SM_TET]);
      if (kCompact) {
        v3 = rec.v[index] ^ v0 ^ v1 ^ v2;
      } else {
        uint first = index * SM_PLAIN_WORDS[SM_TET], missing = 0u;
        v3 = 0u;
        SM_NO_UNROLL for (uint i = 0u; i < 4u; ++i) {
          uint x = rec.v[first + i];
          if (x != v0 && x != v1 && x != v2) {
            v3 = x;
            missing += 1u;
          }
        }
        if (missing != 1u) {
          r.status = MARCH_LOST;
          return r;
        }
      }
      vec3 P0, P1, P2, P3;
      float S0, S1, S2, S3;
      if (carried) {
        P0 = c.P0; S0 = c.S0;
        P1 = c.P2; S1 = c.S2;
        P2 = c.P1; S2 = c.S1;
      } else {
        loadVertex(fr, sc, v0, P0, S0);
        loadVertex(fr, sc, v1, P1, S1);
        loadVertex(fr, sc, v2, P2, S2);
      }
      loadVertex(fr, sc, v3, P3, S3);
      f = tetExitFace(P0.xy, P1.xy, P2.xy, P3.xy, side);
      if (f < 0) f = tetCrossedFace(P0.xy, P1.xy, P2.xy, P3.xy, side);
      if (f < 0) {
        r.status = MARCH_LOST;
        return r;
      }
      // Face f is (f, f + 1 mod 3, 3); the vertex opposite it is f + 2 mod 3.
      e0 = f == 0 ? v0 : f == 1 ? v1 : v2;
      e1 = f == 0 ? v1 : f == 1 ? v2 : v0;
      e2 = v3;
      ce.P0 = f == 0 ? P0 : f == 1 ? P1 : P2;
      ce.S0 = f == 0 ? S0 : f == 1 ? S1 : S2;
      ce.P1 = f == 0 ? P1 : f == 1 ? P2 : P0;
      ce.S1 = f == 0 ? S1 : f == 1 ? S2 : S0;
      ce.P2 = P3;
      ce.S2 = S3;
      ce.P3 = vec3(0.0);
      ce.S3 = 0.0;
      vec3 b;
      triangleCrossing(e0, e1, e2, ce.P0, ce.P1, ce.P2, t, b, slope);
      s = b.x * ce.S0 + b.y * ce.S1 + b.z * ce.S2;
      // Connectivity slot: the rank of the opposite vertex's index among the four (smTetSlot).
      uint x = f == 0 ? v2 : f == 1 ? v0 : v1;
      ref = neighborOf(sc, SM_TET, index, uint(v0 < x) + uint(v1 < x) + uint(v2 < x) + uint(v3 < x));
      if (kShading) {
        vec3 W0 = vertexPosition(sc, v0);
        mat3 J = mat3(vertexPosition(sc, v1) - W0, vertexPosition(sc, v2) - W0, vertexPosition(sc, v3) - W0);
        tetGrad = linearGradient(J, vec3(S1 - S0, S2 - S0, S3 - S0));
      }
    } else {
      uint v[8];
      int entry = decodeElement(sc, type, index, w.k, w.kn, v);
      if (entry < 0) {
        r.status = MARCH_LOST;
        return r;
      }
      elementGeometry(fr, sc, type, v, w, c, carried, g);
      if (!findCrossing(type, v, g, entry, side, w.tIn, w.slopeIn, f, t, slope, s)) {
        r.status = MARCH_LOST;
        return r;
      }
      ref = neighborOf(sc, type, index, uint(f));
      n = smFaceSize(type, uint(f));
      uint l0 = smFaceVert(type, uint(f), 0u), l1 = smFaceVert(type, uint(f), 1u);
      uint l2 = smFaceVert(type, uint(f), 2u), l3 = smFaceVert(type, uint(f), 3u);
      e0 = v[l0]; e1 = v[l1]; e2 = v[l2];
      ce.P0 = g.P[l0]; ce.P1 = g.P[l1]; ce.P2 = g.P[l2];
      ce.S0 = g.S[l0]; ce.S1 = g.S[l1]; ce.S2 = g.S[l2];
      if (n == 4u) {
        e3 = v[l3];
        ce.P3 = g.P[l3];
        ce.S3 = g.S[l3];
      } else {
        ce.P3 = vec3(0.0);
        ce.S3 = 0.0;
      }
    }
    if (side > 0) {
      t = max(t, w.tIn);
      float a = max(w.tIn, tLimit);
      vec3 guess = parametricCenter(type);  // Newton starts at each element's centre
      if (t > a) integrateElement(fr, fp, type, g, tetGrad, w.tIn, t, w.sIn, s, a, t, guess, r.color, r.samples, kNext);
      r.tEnd = t;
      if (r.color.a >= fp.earlyTermination || ref == SM_NO_NEIGHBOR) {
        r.status = MARCH_OK;
        return r;
      }
    } else {
      t = min(t, w.tIn);
      if (t <= tLimit || ref == SM_NO_NEIGHBOR) {
        // Stop here: the forward walk enters this element again through this crossing (its face f,
        // in its own outward order).
        w.next = smElemRef(index, type);
        w.k = uint[4](e0, e1, e2, e3);
        w.kn = n;
        w.tIn = t;
        w.slopeIn = slope;
        w.sIn = s;
        r.status = MARCH_OK;
        return r;
      }
    }
    // Cross face f: the neighbour lists it in reverse (its own outward order).
    w.next = ref;
    if (n == 4u) {
      w.k = uint[4](e3, e2, e1, e0);
      c = FaceCarry(ce.P3, ce.P2, ce.P1, ce.P0, ce.S3, ce.S2, ce.S1, ce.S0);
    } else {
      w.k = uint[4](e2, e1, e0, 0u);
      c = FaceCarry(ce.P2, ce.P1, ce.P0, vec3(0.0), ce.S2, ce.S1, ce.S0, 0.0);
    }
    carried = true;
    w.kn = n;
    w.tIn = t;
    w.slopeIn = slope;
    w.sIn = s;
  }
  return r;
}

#endif
