// Scenes whose word indices would pass 2^31 in the shaders are refused by size alone, naming the
// file, what is too large, the most that fits and "use more ranks"; the sizes at each limit pass.
// (No mesh that large is built: the check takes the counts.)
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

// The message names the file, what is too large, the limit and what would fit.
void expectRefusal(const std::string& msg, const std::string& what, uint64_t limit) {
  EXPECT_NE(msg.find("big.pvtu"), std::string::npos) << msg;
  EXPECT_NE(msg.find(what), std::string::npos) << msg;
  EXPECT_NE(msg.find("at most " + std::to_string(limit) + " "), std::string::npos) << msg;
  EXPECT_NE(msg.find("use more ranks"), std::string::npos) << msg;
}

// Words per element, the larger of record and neighbours: plain tetrahedra 4 (record), pyramids 5,
// wedges 6, hexahedra 8 (record); compact tetrahedra 4 neighbours (their record is one word),
// pyramids 5 and wedges 5 neighbours, hexahedra stay plain.
constexpr uint64_t kPlainWords[4] = {4, 5, 6, 8}, kCompactWords[4] = {4, 5, 5, 8};
const char* const kNames[4] = {"tetrahedra", "pyramids", "wedges", "hexahedra"};

TEST(ShaderIndexRange, EachElementTypeAtItsLimitPassesAndOneMoreIsRefused) {
  const uint64_t words = uint64_t(1) << 31;
  for (bool compact : {false, true}) {
    for (uint32_t t = 0; t < 4; ++t) {
      const uint64_t w = compact ? kCompactWords[t] : kPlainWords[t];
      const uint64_t largest = (words - 1) / w;  // the last word index is 2^31 - 1
      EXPECT_EQ(maxElementsOnRank(t, compact), largest) << kNames[t];
      SceneSizes s;
      s.elements[t] = largest;
      EXPECT_EQ(refusal(s, compact), "") << kNames[t] << (compact ? " compact" : " plain");
      s.elements[t] = largest + 1;
      expectRefusal(refusal(s, compact), kNames[t], largest);
    }
  }
}

TEST(ShaderIndexRange, VerticesAndShellTrianglesAtTheirLimitsPassAndOneMoreIsRefused) {
  const uint64_t words = uint64_t(1) << 31;
  for (bool compact : {false, true}) {
    SceneSizes v;
    v.vertices = (words - 1) / 4;  // 16-byte records
    EXPECT_EQ(v.vertices, kMaxVerticesOnRank);
    EXPECT_EQ(refusal(v, compact), "");
    v.vertices += 1;
    expectRefusal(refusal(v, compact), "vertices", kMaxVerticesOnRank);
    SceneSizes sh;
    sh.shellTriangles = (words - 1) / 3;  // 3 indices each
    EXPECT_EQ(sh.shellTriangles, kMaxShellTrianglesOnRank);
    EXPECT_EQ(refusal(sh, compact), "");
    sh.shellTriangles += 1;
    expectRefusal(refusal(sh, compact), "a shell of", kMaxShellTrianglesOnRank);
  }
}

// Every accepted index fits an element reference (index << 2 | type) without wrapping or becoming
// SM_NO_NEIGHBOR, and its largest word index stays a non-negative 32-bit int.
TEST(ShaderIndexRange, EveryAcceptedElementHasAReferenceAndWordsBelow2To31) {
  for (bool compact : {false, true}) {
    for (uint32_t t = 0; t < 4; ++t) {
      const uint64_t last = maxElementsOnRank(t, compact) - 1;
      EXPECT_LT(last, uint64_t(1) << 30);
      EXPECT_EQ(gpu::smRefIndex(gpu::smElemRef(uint32_t(last), t)), last);
      EXPECT_NE(gpu::smElemRef(uint32_t(last), t), gpu::SM_NO_NEIGHBOR);
      const uint64_t w = compact ? kCompactWords[t] : kPlainWords[t];
      EXPECT_LE(last * w + (w - 1), uint64_t(INT32_MAX));
    }
  }
}

// Counts whose word count would wrap 64 bits are refused, not wrapped into range.
TEST(ShaderIndexRange, AbsurdCountsAreRefusedNotWrapped) {
  for (uint32_t t = 0; t < 4; ++t) {
    SceneSizes s;
    s.elements[t] = (uint64_t(1) << 62) + 1;  // x 4 words wraps to 4
    EXPECT_NE(refusal(s, true), "") << kNames[t];
  }
  SceneSizes v;
  v.vertices = (uint64_t(1) << 62) + 1;
  EXPECT_NE(refusal(v, true), "");
  SceneSizes sh;
  sh.shellTriangles = UINT64_MAX / 3 + 1;
  EXPECT_NE(refusal(sh, true), "");
}

}  // namespace
}  // namespace sm::prep
