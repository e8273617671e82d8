// The order in which shell crossings are found, shared by both tracers: the ray query loop
// (crossing_query.glsl) applies it to each candidate, the ray tracing pipeline's any-hit shader
// (shell_hit.rahit) to each reported intersection, so both pick the same triangle.
#ifndef SM_SHELL_HIT_GLSL
#define SM_SHELL_HIT_GLSL

const uint kNoTriangle = 0xFFFFFFFFu;

// A search for the first shell crossing after (tPrev, triPrev): its state between hit shaders (the
// ray payload of the pipeline tracer). tBest starts at the search's tMax.
struct ShellHit {
  float tPrev;
  uint triPrev;
  float tBest;
  uint tri;  // kNoTriangle until one is found
};

// Whether crossing (t, triangle p) comes after (tPrev, triPrev) and before the best so far, in
// (t, triangle) order, so that crossings at equal t (coincident shells) are each found once.
bool crossingComesFirst(float t, uint p, ShellHit h) {
  bool after = t > h.tPrev || (t == h.tPrev && h.triPrev != kNoTriangle && p > h.triPrev);
  return after && !(t > h.tBest || (h.tri != kNoTriangle && t == h.tBest && p > h.tri));
}

#endif
