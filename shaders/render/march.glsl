// Element marching (the paper's "Per-Segment Volume Integration"): from the element behind a
// segment's entry, walk element to element through the connectivity, finding each exit face with
// the exact crossing predicates (ray_frame.glsl), and integrate the samples of the global grid
// t_k = k dt that fall inside each element. Every walk has a step bound (invariant 6).
#ifndef SM_MARCH_GLSL
#define SM_MARCH_GLSL

#include "ray_frame.glsl"
#include "scene_access.glsl"
#include "interpolate.glsl"

// An element entered through `entryFace` at ray distance tIn (crossing slopes slopeIn, for ties),
// where the scalar is sIn.
// The current element, and the crossing into the next one: the walk enters element `next`
// through face k[0..kn-1] (listed in that element's own outward order) at tIn, where the crossing's
// slopes are slopeIn and the scalar is sIn.
struct Walk {
  uint type;
  uint index;
  uint v[8];
  int entryFace;
  uint next;  // element reference (index << 2 | type)
  uint k[4];
  uint kn;
  float tIn;
  vec2 slopeIn;
  float sIn;
};

struct ElementGeom {
  vec3 P[8];  // projected vertices (xy in the ray frame, z = foot distance)
  vec3 W[8];  // rebased world positions (for Newton in non-tetrahedra)
  float S[8]; // vertex scalars
};

#include "transfer.glsl"

void loadVertex(RayFrame fr, SceneRefs sc, uint id, inout ElementGeom g, uint i) {
  vec3 x = vertexPosition(sc, id);
  g.W[i] = x;
  g.P[i] = projectVertex(fr, x);
  g.S[i] = vertexScalar(sc, id);
}

// Geometry of the element just entered through a face of the previous one: the face's vertices
// were already loaded and projected there (projection is deterministic per vertex, so copying is
// exact); only the others are fetched. A tetrahedron fetches one vertex per step instead of four.
ElementGeom carryGeometry(RayFrame fr, SceneRefs sc, uint type, uint v[8], uint prevV[8], ElementGeom prev,
                          uint prevCount) {
  ElementGeom g;
  SM_NO_UNROLL for (uint i = 0u; i < 8u; ++i) {
    g.P[i] = vec3(0.0);
    g.W[i] = vec3(0.0);
    g.S[i] = 0.0;
  }
  uint pn = prevCount;
  SM_NO_UNROLL for (uint i = 0u; i < SM_NUM_VERTS[type]; ++i) {
    int j = -1;
    SM_NO_UNROLL for (uint k = 0u; k < pn; ++k)
      if (prevV[k] == v[i]) j = int(k);
    if (j >= 0) {
      g.P[i] = prev.P[j];
      g.W[i] = prev.W[j];
      g.S[i] = prev.S[j];
    } else {
      loadVertex(fr, sc, v[i], g, i);
    }
  }
  return g;
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
// Tetrahedron entered through face 3 (decoded tets always are): its other faces share the edges of
// the entry face, whose signs the entry already fixed, so the exit is decided by the signs of the
// three edges to the fourth vertex alone (the paper's "at most 2 tests"). These are the very edge
// signs the general test would compute, so the decision is the same. Returns -1 when an edge is
// degenerate in projection and the general test must decide.
int tetExitFace(ElementGeom g, int side) {
  int e0 = edgeSign(g.P[0].xy, g.P[3].xy);
  int e1 = edgeSign(g.P[1].xy, g.P[3].xy);
  int e2 = edgeSign(g.P[2].xy, g.P[3].xy);
  if (e0 == 0 || e1 == 0 || e2 == 0) return -1;
  if (e1 == side && e0 == -side) return 0;  // face 0 (0, 1, 3)
  if (e2 == side && e1 == -side) return 1;  // face 1 (1, 2, 3)
  if (e0 == side && e2 == -side) return 2;  // face 2 (2, 0, 3)
  return -1;
}

bool findCrossing(uint type, uint v[8], ElementGeom g, int skipFace, int side, float tRef, vec2 slopeRef,
                  out int face, out float t, out vec2 slope, out float s) {
  if (type == SM_TET && skipFace == 3) {
    int f = tetExitFace(g, side);
    if (f >= 0) {
      uint a = smFaceVert(type, uint(f), 0u), b = smFaceVert(type, uint(f), 1u), c = smFaceVert(type, uint(f), 2u);
      vec3 w;
      triangleCrossing(v[a], v[b], v[c], g.P[a], g.P[b], g.P[c], t, w, slope);
      face = f;
      s = w.x * g.S[a] + w.y * g.S[b] + w.z * g.S[c];
      return true;
    }
  }
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
      if (type == SM_TET) {  // convex with planar faces: the first crossing is the only one
        face = int(f);
        t = tc;
        slope = sc;
        s = value;
        return true;
      }
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
// decoding and geometry code (Mesa inlines every call site; compile time grows with size).
MarchResult walk(RayFrame fr, FrameParams fp, inout Walk w, int side, float tLimit) {
  MarchResult r;
  r.color = vec4(0.0);
  r.tEnd = w.tIn;
  r.status = MARCH_STEP_LIMIT;
  r.steps = 0u;
  r.samples = 0u;
  SceneRefs sc = fp.scene;
  ElementGeom g;
  uint prevV[8] = uint[8](0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u);
  uint prevCount = 0u;  // nothing to carry into the first element
  SM_NO_UNROLL for (uint step = 0u; step < fp.maxElementSteps; ++step) {
    r.steps += 1u;
    // Enter the next element: decode it from the face crossed, fetch what the last one did not share.
    uint type = specialisedType(smRefType(w.next)), index = smRefIndex(w.next);
    uint v[8];
    int entry = decodeElement(sc, type, index, w.k, w.kn, v);
    if (entry < 0) {
      r.status = MARCH_LOST;
      return r;
    }
    g = carryGeometry(fr, sc, type, v, prevV, g, prevCount);
    w.type = type;
    w.index = index;
    w.v = v;
    w.entryFace = entry;
    vec3 guess = parametricCenter(type);  // Newton starts at each element's centre

    int f;
    float t, s;
    vec2 slope;
    if (!findCrossing(type, v, g, entry, side, w.tIn, w.slopeIn, f, t, slope, s)) {
      r.status = MARCH_LOST;
      return r;
    }
    uint ref = neighborOf(sc, type, index, faceSlot(type, v, uint(f)));
    uint n = smFaceSize(type, uint(f));
    if (side > 0) {
      t = max(t, w.tIn);
      float a = max(w.tIn, tLimit);
      if (t > a) integrateElement(fr, fp, type, g, w.tIn, t, w.sIn, s, a, t, guess, r.color, r.samples);
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
        SM_NO_UNROLL for (uint i = 0u; i < n; ++i) w.k[i] = v[smFaceVert(type, uint(f), i)];
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
    SM_NO_UNROLL for (uint i = 0u; i < n; ++i) w.k[i] = v[smFaceVert(type, uint(f), n - 1u - i)];
    if (n == 3u) w.k[3] = 0u;
    w.kn = n;
    w.tIn = t;
    w.slopeIn = slope;
    w.sIn = s;
    prevV = v;
    prevCount = SM_NUM_VERTS[type];
  }
  return r;
}

#endif
