// Reading one rank's prepared scene through buffer device addresses.
#ifndef SM_SCENE_ACCESS_GLSL
#define SM_SCENE_ACCESS_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "shared/render_types.h"
#include "shared/xor_codec.h"

// Scene specialisation (docs/DESIGN.md: pay only for what the scene uses).
layout(constant_id = 0) const bool kCompact = true;
layout(constant_id = 1) const uint kTypesPresent = 15u;  // bit t: elements of type t exist

layout(buffer_reference, scalar) readonly buffer SmFloats { float v[]; };
layout(buffer_reference, scalar) readonly buffer SmVec4s { vec4 v[]; };
layout(buffer_reference, scalar) buffer SmUints { uint v[]; };
layout(buffer_reference, scalar) readonly buffer SmUint64s { uint64_t v[]; };
layout(buffer_reference, scalar) buffer SmSegments { Segment v[]; };
layout(buffer_reference, scalar) buffer SmCachedSegments { CachedSegment v[]; };
layout(buffer_reference, scalar) readonly buffer SmParams { FrameParams p; };
layout(buffer_reference, scalar) buffer SmStats { RenderStats s; };

// A scene of one element type makes every test on the type a constant, so the code of the other
// types drops out of the pipeline (docs/DESIGN.md: pay only for what the scene uses).
uint specialisedType(uint t) {
  return kTypesPresent == 1u ? SM_TET : kTypesPresent == 2u ? SM_PYR : kTypesPresent == 4u ? SM_WED
       : kTypesPresent == 8u ? SM_HEX : t;
}

vec2 unpackFloats(uint64_t x) { return uintBitsToFloat(unpackUint2x32(x)); }

// Vertex v's rebased position and scalar: one 16-byte record read as two 64-bit words (every
// per-lane load is a gather on lavapipe: two instead of the four of a float position array and a
// scalar array; a march step fetches one vertex).
vec4 vertexRecord(SceneRefs sc, uint v) {
  SmUint64s r = SmUint64s(sc.vertices);
  return vec4(unpackFloats(r.v[2u * v]), unpackFloats(r.v[2u * v + 1u]));
}
vec3 vertexPosition(SceneRefs sc, uint v) { return vertexRecord(sc, v).xyz; }
float vertexScalar(SceneRefs sc, uint v) { return unpackFloats(SmUint64s(sc.vertices).v[2u * v + 1u]).y; }

uint recordWords(uint type) { return kCompact ? SM_COMPACT_WORDS[type] : SM_PLAIN_WORDS[type]; }

uint neighborOf(SceneRefs sc, uint type, uint index, uint slot) {
  return SmUints(sc.neighbors[type]).v[index * SM_NUM_FACES[type] + slot];
}

#endif
