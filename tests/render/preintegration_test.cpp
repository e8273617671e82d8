// Known answers for the pre-integrated transfer function (CPU, no device).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <random>

#include <glm/vec2.hpp>

#include "render/preintegration.h"

namespace sm::render {
namespace {

scene::TransferFunction constantTf(glm::vec3 rgb, float opacity, double unit) {
  scene::TransferFunction tf;
  tf.table.assign(256, glm::vec4(rgb, opacity));
  tf.lo = 0;
  tf.hi = 1;
  tf.unitDistance = unit;
  return tf;
}

TEST(Preintegration, ConstantMediumIsExact) {
  auto tf = constantTf({0.2f, 0.5f, 0.9f}, 0.8f, 0.5);
  auto t = buildPreintegration(tf);
  const double sigma = 0.8 / 0.5;
  for (double L : {0.0, 0.01, 0.3, 1.0, 2.5, 7.0}) {
    glm::dvec4 v = t.integrate(0.3, 0.7, L);
    double alpha = 1.0 - std::exp(-sigma * L);
    EXPECT_NEAR(v.a, alpha, 1e-6) << L;      // opacity is exact in L
    EXPECT_NEAR(v.b, 0.9 * v.a, 1e-5) << L;  // premultiplied by its own opacity
  }
  EXPECT_NEAR(t.integrate(0.5, 0.5, 20.0).a, 1.0 - std::exp(-sigma * 20.0), 1e-6);
}

// Front to back over 20000 equal steps of a piece of length L whose scalar runs from sf to sb.
glm::dvec4 fineIntegration(const scene::TransferFunction& tf, double sf, double sb, double L) {
  glm::dvec4 acc(0.0);
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    double x = (k + 0.5) / n, sv = sf + (sb - sf) * x;
    glm::dvec4 c = tf.lookup(sv);
    double a = 1.0 - std::exp(-c.a / tf.unitDistance * L / n);
    acc += (1.0 - acc.a) * glm::dvec4(glm::dvec3(c) * a, a);
  }
  return acc;
}

// Against a fine front-to-back integration of a linear scalar through a varying transfer function.
TEST(Preintegration, MatchesFineIntegrationOfLinearPieces) {
  scene::TransferFunction tf = scene::makeTransferFunction("cool-to-warm");
  tf.lo = -1;
  tf.hi = 3;
  tf.unitDistance = 0.7;
  auto t = buildPreintegration(tf);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> s(-1.5, 3.5), len(0.0, 2.0);
  double worst = 0;
  for (int i = 0; i < 300; ++i) {
    double sf = s(rng), sb = s(rng), L = len(rng);
    const glm::dvec4 acc = fineIntegration(tf, sf, sb, L);
    glm::dvec4 v = t.integrate(sf, sb, L);
    for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(v[c] - acc[c]));
  }
  EXPECT_LT(worst, 2e-3);  // colour table resolution: 128 scalar bins, 32 length bins
}

// The same on a log scale over four decades (log-spaced tables), pieces drawn in log space so
// that every decade is tried, short ones within a decade and long ones across the range.
TEST(Preintegration, MatchesFineIntegrationOnALogScale) {
  scene::TransferFunction tf = scene::makeTransferFunction("cool-to-warm");
  tf.lo = 0.01;
  tf.hi = 100;
  tf.scale = scene::ScalarScale::Log;
  tf.unitDistance = 0.7;
  auto t = buildPreintegration(tf);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> decade(-2.5, 2.5), len(0.0, 2.0);
  double worst = 0;
  for (int i = 0; i < 300; ++i) {
    double sf = std::pow(10.0, decade(rng)),
           sb = i % 2 ? sf * (1.0 + 0.2 * decade(rng)) : std::pow(10.0, decade(rng));
    double L = len(rng);
    const glm::dvec4 acc = fineIntegration(tf, sf, sb, L);
    glm::dvec4 v = t.integrate(sf, sb, L);
    for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(v[c] - acc[c]));
  }
  std::printf("[preintegration] log scale: worst channel error %.2g over 300 pieces\n", worst);
  EXPECT_LT(worst, 2e-3);
}

TEST(Preintegration, TransparentFunctionGivesZeros) {
  auto tf = constantTf({1, 1, 1}, 0.0f, 1.0);
  auto t = buildPreintegration(tf);
  EXPECT_EQ(t.integrate(0.2, 0.9, 3.0), glm::dvec4(0.0));
}

// The device reads colours as 21-bit fixed point: decoding is exact (a multiple of 2^-21 is a
// float), within half a step of the input, clamped to [0, 1], and non-finite input gives 0.
TEST(Preintegration, ColorEncodingRoundsToTheNearestStep) {
  const double step = 1.0 / double(1 << PreintegrationTable::kColorBits);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 1000; ++i) {
    glm::vec3 c(u(rng), u(rng), u(rng));
    uint64_t w = PreintegrationTable::encodeColor(c);
    EXPECT_EQ(w >> 63, 0u);
    glm::vec3 d = PreintegrationTable::decodeColor(w);
    for (int k = 0; k < 3; ++k) EXPECT_LE(std::abs(double(d[k]) - c[k]), 0.5 * step + 1e-9) << c[k];
    EXPECT_EQ(PreintegrationTable::encodeColor(d), w);  // decoded values re-encode to themselves
  }
  glm::vec3 edge = PreintegrationTable::decodeColor(
      PreintegrationTable::encodeColor(glm::vec3(-0.5f, 1.0f, std::nanf(""))));
  EXPECT_EQ(edge.r, 0.0f);
  EXPECT_NEAR(edge.g, 1.0, step);
  EXPECT_EQ(edge.b, 0.0f);
}

// deviceWords: colours, then (S[i], S[i+1]) pairs, then the two ends; offsets as the renderer
// passes them to the shader.
TEST(Preintegration, DeviceLayoutHoldsColoursPairsAndEnds) {
  scene::TransferFunction tf = scene::makeTransferFunction("viridis");
  tf.lo = 2;
  tf.hi = 5;
  auto t = buildPreintegration(tf, 16, 4);
  std::vector<uint64_t> w = t.deviceWords();
  const size_t nc = t.colors.size(), ns = t.cumulative.size();
  ASSERT_EQ(w.size(), nc + (ns - 1) + 4);
  EXPECT_EQ(t.deviceColorBytes(), nc * 8);
  for (size_t i = 0; i < nc; ++i)
    ASSERT_EQ(PreintegrationTable::decodeColor(w[i]), t.colors[i]) << i;
  auto floats = [](uint64_t x) {
    return glm::vec2(std::bit_cast<float>(uint32_t(x)), std::bit_cast<float>(uint32_t(x >> 32)));
  };
  for (size_t i = 0; i + 1 < ns; ++i) {
    ASSERT_EQ(floats(w[nc + i]), glm::vec2(t.cumulative[i], t.cumulative[i + 1])) << i;
  }
  const size_t e = nc + ns - 1;
  EXPECT_EQ(glm::vec4(floats(w[e]), floats(w[e + 1])), t.below);
  EXPECT_EQ(glm::vec4(floats(w[e + 2]), floats(w[e + 3])), t.above);
  EXPECT_EQ(glm::vec3(t.below), glm::vec3(tf.table.front()));
  EXPECT_EQ(glm::vec3(t.above), glm::vec3(tf.table.back()));
}

// Outside [lo, hi] the function is its end value: a piece entirely below the range, entirely
// above it, or crossing it, against the closed form of each part.
TEST(Preintegration, OutsidePiecesUseTheEndValuesInClosedForm) {
  scene::TransferFunction tf = scene::makeTransferFunction("inferno");
  tf.lo = 0;
  tf.hi = 1;
  tf.unitDistance = 0.5;
  for (auto& e : tf.table) e.a = 0.3f + 0.5f * (&e - tf.table.data()) / 255.0f;
  auto t = buildPreintegration(tf);
  auto closed = [](glm::vec4 c, double sigma, double L) {
    double a = 1.0 - std::exp(-sigma * L);
    return glm::dvec4(glm::dvec3(c) * a, a);
  };
  const glm::vec4 lo = tf.table.front(), hi = tf.table.back();
  glm::dvec4 below = t.integrate(-3.0, -1.0, 0.8), above = t.integrate(4.0, 2.0, 0.8);
  glm::dvec4 wantBelow = closed(lo, lo.a / 0.5, 0.8), wantAbove = closed(hi, hi.a / 0.5, 0.8);
  for (int c = 0; c < 4; ++c) {
    EXPECT_NEAR(below[c], wantBelow[c], 1e-6) << c;
    EXPECT_NEAR(above[c], wantAbove[c], 1e-6) << c;
  }
  // From -1 to 2 over L = 0.9: a third below, a third inside, a third above, front to back.
  glm::dvec4 front = closed(lo, lo.a / 0.5, 0.3), back = closed(hi, hi.a / 0.5, 0.3);
  glm::dvec4 inside = t.integrate(0.0, 1.0, 0.3);
  glm::dvec4 want = front + (1.0 - front.a) * inside;
  want += (1.0 - want.a) * back;
  glm::dvec4 got = t.integrate(-1.0, 2.0, 0.9);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(got[c], want[c], 1e-6) << c;
}

// A transfer function over a single value maps every scalar to its table's middle entry
// (TransferFunction::lookup), outside pieces included.
TEST(Preintegration, ConstantRangeUsesTheMiddleEntryEverywhere) {
  scene::TransferFunction tf = scene::makeTransferFunction("cool-to-warm");
  tf.lo = tf.hi = 2.0;
  tf.unitDistance = 1.0;
  auto t = buildPreintegration(tf);
  glm::dvec4 mid = tf.lookup(2.0);
  for (auto [sf, sb] : {std::pair{-10.0, -8.0}, {1.9, 2.1}, {7.0, 30.0}, {-4.0, 6.0}}) {
    glm::dvec4 v = t.integrate(sf, sb, 0.7);
    double a = 1.0 - std::exp(-mid.a * 0.7);
    EXPECT_NEAR(v.a, a, 1e-6) << sf << " " << sb;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(v[c], mid[c] * a, 1e-5) << sf << " " << sb << " " << c;
  }
}

}  // namespace
}  // namespace sm::render
