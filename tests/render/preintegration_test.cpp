// Known answers for the pre-integrated transfer function (CPU, no device).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

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
    glm::dvec4 acc(0.0);
    const int n = 20000;
    for (int k = 0; k < n; ++k) {
      double x = (k + 0.5) / n, sv = sf + (sb - sf) * x;
      glm::dvec4 c = tf.lookup(sv);
      double a = 1.0 - std::exp(-c.a / tf.unitDistance * L / n);
      acc += (1.0 - acc.a) * glm::dvec4(glm::dvec3(c) * a, a);
    }
    glm::dvec4 v = t.integrate(sf, sb, L);
    for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(v[c] - acc[c]));
  }
  EXPECT_LT(worst, 2e-3);  // colour table resolution: 128 scalar bins, 32 length bins
}

TEST(Preintegration, TransparentFunctionGivesZeros) {
  auto tf = constantTf({1, 1, 1}, 0.0f, 1.0);
  auto t = buildPreintegration(tf);
  EXPECT_EQ(t.integrate(0.2, 0.9, 3.0), glm::dvec4(0.0));
}

}  // namespace
}  // namespace sm::render
