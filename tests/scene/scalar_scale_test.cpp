// The transfer function's scalar scale (`--log-scale`): table coordinates and their inverse,
// lookups, opacity points and legend labels on a log scale, and the ranges it refuses.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/error.h"
#include "scene/legend.h"
#include "scene/transfer_function.h"

namespace sm::scene {
namespace {

TransferFunction logTable(double lo, double hi, int entries = 256) {
  TransferFunction tf = makeTransferFunction("grayscale", entries);
  tf.lo = lo;
  tf.hi = hi;
  tf.scale = ScalarScale::Log;
  return tf;
}

TEST(ScalarScale, LogCoordinatesAreDecadesOfTheRange) {
  const TransferFunction tf = logTable(1.0, 1000.0);
  EXPECT_DOUBLE_EQ(tf.coordinate(1.0), 0.0);
  EXPECT_NEAR(tf.coordinate(10.0), 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(tf.coordinate(100.0), 2.0 / 3.0, 1e-15);
  EXPECT_DOUBLE_EQ(tf.coordinate(1000.0), 1.0);
  EXPECT_DOUBLE_EQ(tf.coordinate(5000.0), 1.0);  // above: the last entry
  for (double v : {0.5, 0.0, -3.0, -double(INFINITY)}) EXPECT_DOUBLE_EQ(tf.coordinate(v), 0.0) << v;
  for (double x : {0.0, 0.125, 1.0 / 3.0, 0.5, 0.9, 1.0})
    EXPECT_NEAR(tf.coordinate(tf.valueAt(x)), x, 1e-14) << x;
  EXPECT_NEAR(tf.valueAt(0.5), std::sqrt(1000.0), 1e-12);  // the geometric middle
  // The grayscale ramp's opacity at a third of the way: entry 85 of 256 exactly.
  EXPECT_NEAR(tf.lookup(10.0).a, 1.0 / 3.0, 1e-7);
  EXPECT_EQ(tf.lookup(-1.0), glm::dvec4(tf.table.front()));
  // Non-finite: the NaN colour, transparent unless a NaN opacity is given.
  EXPECT_EQ(tf.lookup(NAN), glm::dvec4(glm::dvec3(tf.nanColor), 0.0));
  // The linear scale is unchanged.
  TransferFunction lin = tf;
  lin.scale = ScalarScale::Linear;
  EXPECT_NEAR(lin.coordinate(10.0), 9.0 / 999.0, 1e-15);
  EXPECT_NEAR(lin.valueAt(0.5), 500.5, 1e-12);
}

// Opacity points are data values: on a log scale each entry takes the opacity at its own
// (log-spaced) value.
TEST(ScalarScale, OpacityPointsFollowTheEntriesValues) {
  TransferFunction tf = logTable(1.0, 1e4, 257);  // entry 64 k holds 10^k
  const OpacityPoint points[] = {{10.0, 0.0}, {100.0, 0.9}};
  setOpacityPoints(tf, points);
  EXPECT_FLOAT_EQ(tf.table[0].a, 0.0f);
  EXPECT_FLOAT_EQ(tf.table[64].a, 0.0f);                                            // 10
  EXPECT_FLOAT_EQ(tf.table[96].a, float(0.9 * (std::sqrt(1000.0) - 10.0) / 90.0));  // 31.6
  EXPECT_FLOAT_EQ(tf.table[128].a, 0.9f);                                           // 100
  EXPECT_FLOAT_EQ(tf.table[256].a, 0.9f);
}

TEST(ScalarScale, ALogScaleNeedsAPositiveRange) {
  for (auto [lo, hi] : {std::pair{0.0, 1.0}, {-2.0, 5.0}, {1.0, double(INFINITY)}}) {
    try {
      checkScale(logTable(lo, hi));
      ADD_FAILURE() << lo << " .. " << hi << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("--log-scale: a log scale needs a positive range"),
                std::string::npos)
          << e.what();
    }
  }
  EXPECT_NO_THROW(checkScale(logTable(1e-30, 1e30)));
  EXPECT_NO_THROW(checkScale(logTable(2.0, 2.0)));  // a constant positive field
  TransferFunction lin = logTable(-2.0, 5.0);
  lin.scale = ScalarScale::Linear;
  EXPECT_NO_THROW(checkScale(lin));
}

// The legend says which scale it shows: its title gains " (log)", which widens its layout.
TEST(ScalarScale, TheLegendNamesALogScale) {
  const std::string title = "a rather long field name";
  TransferFunction tf = logTable(1.0, 2.0);
  const LegendLayout log = legendLayout(400, 300, tf, title);
  tf.scale = ScalarScale::Linear;
  const LegendLayout linear = legendLayout(400, 300, tf, title);
  EXPECT_LT(log.left, linear.left);
  EXPECT_EQ(log.right, linear.right);
}

}  // namespace
}  // namespace sm::scene
