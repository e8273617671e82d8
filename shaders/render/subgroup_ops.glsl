// Subgroup votes and reductions behind one switch (SM_SUBGROUPS, set by the stage file). Where a
// stage has no subgroup operations each falls back to the invocation's own value: the votes
// (smAny, smMax) only choose how much work a SIMD batch shares, never a result, and the counters
// then add one invocation's value at a time.
#ifndef SM_SUBGROUP_OPS_GLSL
#define SM_SUBGROUP_OPS_GLSL

#if SM_SUBGROUPS
bool smAny(bool b) { return subgroupAny(b); }
uint smMax(uint n) { return subgroupMax(n); }

// Adds a subgroup's values to a counter. Every atomic sits behind a branch on a subgroup total:
// the total is uniform, so lavapipe branches around the block instead of masking it, and the
// atomic's per-lane loop (eight iterations with a stack round trip each, inactive lanes included)
// runs only when there is something to add. Thirteen such loops cost about 25 ms of a 512² frame
// whose rays all miss; rare counters are now skipped and frequent ones run once.
#define SM_FLUSH(counter, value)                        \
  {                                                    \
    uint total_ = subgroupAdd(value);                  \
    if (total_ != 0u) {                                \
      if (subgroupElect()) atomicAdd(counter, total_); \
    }                                                  \
  }
// The same into a 64-bit counter of two words (counters.glsl).
#define SM_FLUSH_WIDE(lo, hi, value)                                  \
  {                                                                  \
    uint total_ = subgroupAdd(value);                                \
    if (total_ != 0u) {                                              \
      if (subgroupElect()) SM_ADD_WITH_CARRY(lo, hi, total_);        \
    }                                                                \
  }
#else
bool smAny(bool b) { return b; }
uint smMax(uint n) { return n; }
#define SM_FLUSH(counter, value)                 \
  {                                             \
    uint total_ = (value);                      \
    if (total_ != 0u) atomicAdd(counter, total_); \
  }
#define SM_FLUSH_WIDE(lo, hi, value)                      \
  {                                                      \
    uint total_ = (value);                               \
    if (total_ != 0u) SM_ADD_WITH_CARRY(lo, hi, total_); \
  }
#endif

#endif
