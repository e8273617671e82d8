// Element marching (the paper's "Per-Segment Volume Integration"): from the element behind a
// segment's entry, walk element to element through the connectivity, finding each exit face with
// the exact crossing predicates (ray_frame.glsl), and integrate the samples of the global grid
// t_k = k dt that fall inside each element. Every walk has a step bound (invariant 6).
#ifndef SM_MARCH_GLSL
#define SM_MARCH_GLSL

void loadVertex(RayFrame fr, SceneRefs sc, uint id, out vec3 P, out float S) {
  vec4 r = vertexRecord(sc, id);
  P = projectVertex(fr, r.xyz);
  S = r.w;
}

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
// decoding and geometry code per type (Mesa inlines every call site; compile time grows with
// size). Each step takes one of two paths, tetrahedra and the rest, which meet again at the exit
// crossing.
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
  TfCache tfc = emptyTfCache();
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
    vec3 guess = parametricCenter(type);  // Newton's start: the centre (element-exact: stepOf's)
    if (type == SM_TET) {
      // Decoded as (k0, k2, k1, fourth), entered through face 3 (xor_codec.h); the entry face's
      // vertices come from the carry.
      if (w.kn != 3u) {
        r.status = MARCH_LOST;
        return r;
      }
      // All four neighbours, read with the record: the one behind the exit face is known only
      // after the vertex fetch, and reading it then put a third dependent gather on each step's
      // path (two 64-bit words; 7% off the demo frame at 4 times the default step).
      SmUint64s nb = SmUint64s(sc.neighbors[SM_TET]);
      uvec2 n01 = unpackUint2x32(nb.v[2u * index]), n23 = unpackUint2x32(nb.v[2u * index + 1u]);
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
      uint slot = uint(v0 < x) + uint(v1 < x) + uint(v2 < x) + uint(v3 < x);
      ref = slot == 0u ? n01.x : slot == 1u ? n01.y : slot == 2u ? n23.x : n23.y;
      if (kShading) {
        vec3 W0 = vertexPosition(sc, v0);
        mat3 J = mat3(vertexPosition(sc, v1) - W0, vertexPosition(sc, v2) - W0, vertexPosition(sc, v3) - W0);
        tetGrad = linearGradient(J, vec3(S1 - S0, S2 - S0, S3 - S0));
      }
    } else {
      // One inlined copy per type, so that each has constant tables (element_step.glsl).
      if (type == SM_HEX)
        f = stepOf(fr, sc, SM_HEX, index, w, c, carried, side, g, t, slope, s, ref, n, e0, e1, e2, e3, ce, guess);
      else if (type == SM_WED)
        f = stepOf(fr, sc, SM_WED, index, w, c, carried, side, g, t, slope, s, ref, n, e0, e1, e2, e3, ce, guess);
      else
        f = stepOf(fr, sc, SM_PYR, index, w, c, carried, side, g, t, slope, s, ref, n, e0, e1, e2, e3, ce, guess);
      if (f < 0) {
        r.status = MARCH_LOST;
        return r;
      }
    }
    if (side > 0) {
      t = max(t, w.tIn);
      float a = max(w.tIn, tLimit);
      if (t > a) integrateElement(fr, fp, type, g, tetGrad, w.tIn, t, w.sIn, s, a, t, guess, r.color, r.samples, kNext, tfc);
      r.tEnd = t;
      // Past the clip planes' span nothing more is sampled: the walk stops as if it left the volume.
      if (r.color.a >= fp.earlyTermination || ref == SM_NO_NEIGHBOR || (kClip && t >= fr.clipHi)) {
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
