// Scenes whose word indices would pass 2^31 in the shaders are refused by size alone, naming the
// file and what is too large; the sizes just below each limit pass. (No mesh that large is built:
// the check takes the counts.)
#include <gtest/gtest.h>

#include <string>

#include "common/error.h"
#include "prep/prepare.h"

namespace sm::prep {
namespace {

std::string refusal(const SceneSizes& s, bool compact) {
  try {
    checkShaderIndexRange("big.pvtu", s, compact);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ShaderIndexRange, EachSizeJustBelowItsLimitPassesAndOneMoreIsRefused) {
  const uint64_t words = uint64_t(1) << 31;
  // Words per element: plain tetrahedra 4 (record), pyramids 5, wedges 6, hexahedra 8 (record),
  // hexahedra 6 neighbours; compact tetrahedra 4 neighbours (their record is one word).
  const uint64_t plainWords[4] = {4, 5, 6, 8}, compactWords[4] = {4, 5, 5, 8};
  const char* names[4] = {"tetrahedra", "pyramids", "wedges", "hexahedra"};
  for (bool compact : {false, true}) {
    for (int t = 0; t < 4; ++t) {
      const uint64_t w = compact ? compactWords[t] : plainWords[t];
      SceneSizes s;
      s.elements[t] = (words - 1) / w;
      EXPECT_EQ(refusal(s, compact), "") << names[t];
      s.elements[t] += 1;
      const std::string msg = refusal(s, compact);
      EXPECT_NE(msg.find("big.pvtu"), std::string::npos) << msg;
      EXPECT_NE(msg.find(names[t]), std::string::npos) << msg;
      EXPECT_NE(msg.find("use more ranks"), std::string::npos) << msg;
    }
  }
  SceneSizes v;
  v.vertices = (words - 1) / 4;
  EXPECT_EQ(refusal(v, true), "");
  v.vertices += 1;
  EXPECT_NE(refusal(v, true).find("vertices"), std::string::npos);
  SceneSizes sh;
  sh.shellTriangles = (words - 1) / 3;
  EXPECT_EQ(refusal(sh, true), "");
  sh.shellTriangles += 1;
  EXPECT_NE(refusal(sh, true).find("a shell of"), std::string::npos);
}

}  // namespace
}  // namespace sm::prep
