// The element walk's state (march.glsl), declared before the integration and step code that take it.
#ifndef SM_WALK_STATE_GLSL
#define SM_WALK_STATE_GLSL

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

// Geometry of a pyramid, wedge or hexahedron, indexed by constants only (element_step.glsl: lavapipe
// compiles a dynamically indexed local array to per-lane scalar loads and masked stores). Tetrahedra
// keep theirs in plain variables.
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

#endif
