// 64-bit counters from 32-bit atomics, for counts that pass 2^32 on large images (samples, element
// steps) on devices without 64-bit atomics: the add that wraps the low word carries into the
// high one. The pair is exact once every add has finished (read after the frame).
#ifndef SM_COUNTERS_GLSL
#define SM_COUNTERS_GLSL

#define SM_ADD_WITH_CARRY(lo, hi, v) \
  if (atomicAdd(lo, v) > 0xffffffffu - (v)) atomicAdd(hi, 1u)

#endif
