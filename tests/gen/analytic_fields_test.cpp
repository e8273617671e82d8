#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"
#include "gen/generate.h"

namespace sm::gen {
namespace {

TEST(AnalyticFields, AddsFourFiniteFieldsWithTimeSteps) {
  auto m = cube(CubeSplit::Hex, 8, 3.0);
  addAnalyticFields(m, 4);
  ASSERT_EQ(m.fields.size(), 4u);
  EXPECT_EQ(m.timeValues, (std::vector<double>{0.0, 1.0 / 3, 2.0 / 3, 1.0}));
  for (const char* name : {"linear", "shock", "vortex", "density"}) {
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
  EXPECT_EQ(m.fields.size(), 4u);
  EXPECT_EQ(m.findField("shock")->numSteps(), 2u);
}

// The bow shock stands off the nose of a unit body at the origin facing -x: free stream (1) ahead
// of it, the strong-shock jump (about 5.5 and more in the shock layer) just behind it on the axis,
// a weaker oblique jump off the axis, and a wake below the shock layer's density behind the body.
TEST(AnalyticFields, DensityHasABowShockAheadOfTheBody) {
  mesh::UnstructuredMesh m;
  m.points = {{-3.0, 0, 0}, {-0.2, 0, 0}, {-0.2, 0, 3.0}, {6.0, 0, 3.0}, {6.0, 0, 0}, {-1.0, 0, 0}};
  addAnalyticFields(m, 1);
  const std::vector<float>& d = m.findField("density")->steps[0];
  EXPECT_NEAR(d[0], 1.0, 1e-6);  // upstream
  EXPECT_NEAR(d[5], 1.0, 1e-3);  // ahead of the shock on the axis
  EXPECT_GT(d[1], 5.5);          // shock layer at the nose
  EXPECT_LT(d[2], 1.01);         // off the axis the shock is further downstream
  EXPECT_GT(d[3], 1.5);          // behind the oblique part: weaker jump
  EXPECT_LT(d[3], 4.0);
  EXPECT_LT(d[4], d[3]);  // the wake
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
