// Bridge that lets one header be included by both C++ and GLSL (glslang,
// GL_GOOGLE_include_directive). Only the common subset is used in shared headers: uint/int/float
// scalars, fixed arrays, plain functions. In C++ everything lives in namespace sm::gpu.
#ifndef SM_GLSL_CPP_H
#define SM_GLSL_CPP_H

#ifdef __cplusplus
#include <cstdint>
#define SM_BEGIN_NAMESPACE namespace sm::gpu {
#define SM_END_NAMESPACE }
#define SM_FN constexpr inline
#define SM_CONST inline constexpr
// Fixed-size array definitions: SM_ARRAY(uint, NAME, 4) SM_ARRAY_INIT(uint, 4)(DATA) ...
#define SM_IN_ARR(T, name, n) const T name[n]
#define SM_OUT_ARR(T, name, n) T name[n]
#define SM_INOUT(T, name) T& name
#define SM_OUT(T, name) T& name
#define SM_U(x) x##u
#define SM_NO_UNROLL
#define SM_UNROLL
#else
#define SM_BEGIN_NAMESPACE
#define SM_END_NAMESPACE
#define SM_FN
#define SM_CONST const
#define SM_IN_ARR(T, name, n) T name[n]
#define SM_OUT_ARR(T, name, n) out T name[n]
#define SM_INOUT(T, name) inout T name
#define SM_OUT(T, name) out T name
#define SM_U(x) x##u
// Loops over faces and vertices stay loops (SM_NO_UNROLL) where they run for a type known only per
// lane: unrolled for every element type they multiply code size, and with it Mesa's shader compile
// time (seconds per pipeline on lavapipe). SM_UNROLL marks loops that run for a literal type
// (shaders/render/element_step.glsl), where unrolling turns every array index into a constant.
#extension GL_EXT_control_flow_attributes : require
#define SM_NO_UNROLL [[dont_unroll]]
#define SM_UNROLL [[unroll]]
#endif

#ifdef __cplusplus
namespace sm::gpu {
using uint = uint32_t;
}
#endif

#endif
