#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"
#include "gen/generate.h"

namespace sm::gen {
namespace {

TEST(AnalyticFields, AddsThreeFiniteFieldsWithTimeSteps) {
  auto m = cube(CubeSplit::Hex, 8, 3.0);
  addAnalyticFields(m, 4);
  ASSERT_EQ(m.fields.size(), 3u);
  EXPECT_EQ(m.timeValues, (std::vector<double>{0.0, 1.0 / 3, 2.0 / 3, 1.0}));
  for (const char* name : {"linear", "shock", "vortex"}) {
    const mesh::Field* f = m.findField(name);
    ASSERT_NE(f, nullptr) << name;
    ASSERT_EQ(f->numSteps(), 4u);
    for (const auto& step : f->steps) {
      ASSERT_EQ(step.size(), m.numPoints());
      for (float v : step) ASSERT_TRUE(std::isfinite(v)) << name;
    }
  }
  // Calling again replaces the fields rather than adding copies.
  addAnalyticFields(m, 2);
  EXPECT_EQ(m.fields.size(), 3u);
  EXPECT_EQ(m.findField("shock")->numSteps(), 2u);
}

TEST(AnalyticFields, LinearIsAffineInTheCoordinatesAndConstantInTime) {
  auto m = cube(CubeSplit::Tets5, 4, 2.0);
  addAnalyticFields(m, 3);
  const mesh::Field& f = *m.findField("linear");
  for (size_t i = 0; i < m.numPoints(); ++i) {
    const glm::dvec3 p = m.points[i] / 2.0;
    EXPECT_NEAR(f.steps[0][i], (p.x + 2 * p.y + 3 * p.z) / 6, 1e-6);
    EXPECT_EQ(f.steps[0][i], f.steps[1][i]);
    EXPECT_EQ(f.steps[0][i], f.steps[2][i]);
  }
  auto r = mesh::fieldRange(f);
  EXPECT_EQ(r.lo, 0.0);
  EXPECT_NEAR(r.hi, 1.0, 1e-6);
}

TEST(AnalyticFields, ShockAndVortexMoveAndStayInRange) {
  auto m = cube(CubeSplit::Hex, 24);
  addAnalyticFields(m, 3);
  const mesh::Field& shock = *m.findField("shock");
  const mesh::Field& vortex = *m.findField("vortex");
  for (uint64_t s = 0; s < 3; ++s) {
    auto rs = mesh::fieldRange(shock, s), rv = mesh::fieldRange(vortex, s);
    EXPECT_GE(rs.lo, 0.99);
    EXPECT_LE(rs.hi, 4.2);
    EXPECT_GT(rs.hi - rs.lo, 2.0) << "the shock jump is in the domain at step " << s;
    EXPECT_GE(rv.lo, 0.0);
    EXPECT_LE(rv.hi, 1.0 + 1e-6);
    EXPECT_GT(rv.hi, 0.8) << "the vortex core is in the domain at step " << s;
  }
  EXPECT_NE(shock.steps[0], shock.steps[2]);
  EXPECT_NE(vortex.steps[0], vortex.steps[2]);
}

TEST(AnalyticFields, RejectsNoSteps) {
  auto m = singleElement(mesh::CellType::Tet);
  EXPECT_THROW(addAnalyticFields(m, 0), Error);
}

}  // namespace
}  // namespace sm::gen
