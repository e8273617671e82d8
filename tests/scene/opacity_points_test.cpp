// Opacity control points (`--opacity`, scene::setOpacityPoints): known table entries, steps,
// constant ends, and one-line errors.
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"
#include "scene/transfer_function.h"

namespace sm::scene {
namespace {

// 257 entries over [10, 20]: entry i holds the value 10 + i / 25.6, so values at multiples of
// 0.3125 (= 8 entries) fall on entries exactly.
TransferFunction table(double lo = 10, double hi = 20) {
  TransferFunction tf = makeTransferFunction("viridis", 257);
  tf.lo = lo;
  tf.hi = hi;
  return tf;
}

float alphaAtValue(const TransferFunction& tf, double v) {
  return tf.table[size_t(std::lround((v - tf.lo) / (tf.hi - tf.lo) * 256))].a;
}

TEST(OpacityPoints, InterpolateLinearlyBetweenPointsInDataValues) {
  TransferFunction tf = table();
  const glm::vec3 rgb = glm::vec3(tf.table[100]);
  const OpacityPoint points[] = {{12.5, 0.0}, {15.0, 0.8}, {17.5, 0.2}};
  setOpacityPoints(tf, points);
  EXPECT_FLOAT_EQ(alphaAtValue(tf, 10.0), 0.0f);  // the first point's opacity below it
  EXPECT_FLOAT_EQ(alphaAtValue(tf, 12.5), 0.0f);
  EXPECT_FLOAT_EQ(alphaAtValue(tf, 13.75), 0.4f);  // half way up
  EXPECT_FLOAT_EQ(alphaAtValue(tf, 15.0), 0.8f);
  EXPECT_FLOAT_EQ(alphaAtValue(tf, 16.25), 0.5f);  // half way down
  EXPECT_FLOAT_EQ(alphaAtValue(tf, 20.0), 0.2f);   // the last point's above it
  EXPECT_EQ(glm::vec3(tf.table[100]), rgb);        // colours untouched
}

TEST(OpacityPoints, EqualValuesMakeAStepAndOnePointIsConstant) {
  TransferFunction tf = table();
  const OpacityPoint step[] = {{15.0, 0.0}, {15.0, 1.0}};
  setOpacityPoints(tf, step);
  EXPECT_FLOAT_EQ(alphaAtValue(tf, 14.6875), 0.0f);
  EXPECT_FLOAT_EQ(alphaAtValue(tf, 15.0), 1.0f);  // the later point holds from the step on
  EXPECT_FLOAT_EQ(alphaAtValue(tf, 20.0), 1.0f);
  const OpacityPoint one[] = {{-1e9, 0.3}};
  setOpacityPoints(tf, one);
  for (const glm::vec4& e : tf.table) EXPECT_FLOAT_EQ(e.a, 0.3f);
}

// A constant field's range (lo == hi) maps every scalar to the table's middle: every entry takes
// the opacity at that one value.
TEST(OpacityPoints, AConstantRangeTakesTheOpacityAtItsValue) {
  TransferFunction tf = table(4, 4);
  const OpacityPoint points[] = {{0.0, 0.0}, {8.0, 1.0}};
  setOpacityPoints(tf, points);
  for (const glm::vec4& e : tf.table) EXPECT_FLOAT_EQ(e.a, 0.5f);
}

TEST(OpacityPoints, ImpossiblePointsAreOneLineErrors) {
  auto message = [](std::vector<OpacityPoint> points) {
    TransferFunction tf = table();
    try {
      setOpacityPoints(tf, points);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message({}), "--opacity: no opacity points");
  EXPECT_EQ(message({{1, 0.5}, {0, 0.5}}),
            "--opacity: point 2 (value 0) comes before point 1 (value 1): give the points in "
            "increasing value");
  EXPECT_EQ(message({{1, 1.5}}),
            "--opacity: point 1 (1:1.5) needs a finite value and an opacity in [0, 1]");
  EXPECT_EQ(message({{0, 0}, {NAN, 1}}),
            "--opacity: point 2 (nan:1) needs a finite value and an opacity in [0, 1]");
}

}  // namespace
}  // namespace sm::scene
