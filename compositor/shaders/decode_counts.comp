#version 460
// Step 2, after the exchange: unpacks the counters received from every source into 32-bit counts,
// source-major (counts[s * perSource + j] is source s's list length for this rank's position j:
// the j-th pixel it owns).
#extension GL_GOOGLE_include_directive : require
#include "dc_common.glsl"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { DcDecodePush pc; };

void main() {
  uint i = smInvocationIndex(gl_WorkGroupSize.x);
  if (i >= pc.perSource * pc.sources) return;
  uint s = i / pc.perSource, j = i % pc.perSource;
  uint perWord = 32u / pc.bits;
  uint word = DcUints(pc.words).v[s * pc.wordsPerSource + j / perWord];
  uint mask = (1u << pc.bits) - 1u;
  DcUints(pc.counts).v[i] = (word >> ((j % perWord) * pc.bits)) & mask;
}
