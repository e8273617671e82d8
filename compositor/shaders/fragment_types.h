// Fragment formats shared by the compositor's C++ and GLSL.
#ifndef DC_FRAGMENT_TYPES_H
#define DC_FRAGMENT_TYPES_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/vec4.hpp>
namespace sm::comp {
using vec4 = glm::vec4;
using uint = uint32_t;
#define DC_CONST inline constexpr
#define DC_FN constexpr inline
#else
#define DC_CONST const
#define DC_FN
#endif

DC_CONST uint DC_TWO_PASS = 0u;
DC_CONST uint DC_FIXED_DROP = 1u;
DC_CONST uint DC_FIXED_MERGE = 2u;
DC_CONST uint DC_ENCODING_FLOAT = 0u;  // 20 bytes: premultiplied rgba + depth
DC_CONST uint DC_ENCODING_RGBA8 = 1u;  // 8 bytes: rgba8 (premultiplied) + depth

struct DcFragment {
  vec4 color;   // premultiplied rgb, opacity
  float depth;  // entry distance along the ray
};

struct DcPackedFragment {
  uint rgba8;
  float depth;
};

#ifdef __cplusplus
static_assert(sizeof(DcFragment) == 20);
static_assert(sizeof(DcPackedFragment) == 8);
}  // namespace sm::comp
#else
DcFragment dcOver(DcFragment front, DcFragment back) {
  DcFragment r;
  r.color = front.color + (1.0 - front.color.a) * back.color;
  r.depth = front.depth;
  return r;
}
DcPackedFragment dcPack(DcFragment f) {
  DcPackedFragment p;
  p.rgba8 = packUnorm4x8(f.color);
  p.depth = f.depth;
  return p;
}
DcFragment dcUnpack(DcPackedFragment p) {
  DcFragment f;
  f.color = unpackUnorm4x8(p.rgba8);
  f.depth = p.depth;
  return f;
}
#endif

#endif
