// Known answers for the reference's interpolation: VTK's shape functions (values computed with
// VTK 9.1), exact inversion of the isoparametric map on distorted elements, exact reproduction of
// linear fields on affine elements, clamping, and degenerate inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "ref/interpolation.h"
#include "test_meshes.h"

namespace sm::ref {
namespace {

using mesh::CellType;

struct VtkPoint {
  glm::dvec3 rst, x;
};
struct VtkCase {
  CellType type;
  std::vector<glm::dvec3> corners;
  std::vector<VtkPoint> points;
};

// vtkCell::EvaluateLocation on distorted (non-affine) cells, printed with %.17g.
std::vector<VtkCase> vtkCases() {
  return {
      {CellType::Pyramid,
       {{0, 0, 0}, {1.1, 0.05, -0.1}, {0.95, 1.2, 0.1}, {-0.1, 0.9, 0.05}, {0.4, 0.6, 1.3}},
       {{{0.2, 0.3, 0.4}, {0.2722, 0.41699999999999998, 0.52239999999999998}},
        {{0.7, 0.1, 0.85}, {0.45347500000000007, 0.53137500000000004, 1.0968249999999999}},
        {{0.05, 0.6, 0.15}, {0.054475000000000003, 0.55749999999999988, 0.22007499999999999}}}},
      {CellType::Wedge,
       {{0, 0, 0},
        {0.1, 1.1, -0.05},
        {1.2, 0.1, 0.1},
        {0.05, -0.1, 1.0},
        {0.0, 1.2, 1.3},
        {1.0, 0.1, 0.9}},
       {{{0.2, 0.3, 0.4}, {0.35799999999999998, 0.23800000000000004, 0.42400000000000004}},
        {{0.7, 0.1, 0.85}, {0.12200000000000001, 0.8224999999999999, 1.0162499999999999}},
        {{0.05, 0.6, 0.15}, {0.70887499999999992, 0.11049999999999999, 0.19212499999999999}}}},
      {CellType::Hex,
       {{0, 0, 0},
        {1.2, 0.1, -0.1},
        {1.1, 1.0, 0.2},
        {-0.1, 1.1, 0.0},
        {0.1, -0.1, 1.1},
        {0.9, 0.0, 1.2},
        {1.3, 1.2, 0.9},
        {0.0, 0.9, 1.0}},
       {{{0.2, 0.3, 0.4}, {0.23000000000000001, 0.29559999999999997, 0.43000000000000005}},
        {{0.7, 0.1, 0.85}, {0.70674999999999999, 0.096299999999999997, 0.96675}},
        {{0.05, 0.6, 0.15}, {0.014250000000000016, 0.63679999999999981, 0.15925}}}},
  };
}

TEST(Interpolation, ShapeFunctionsMatchVtk) {
  // vtkCell::InterpolationFunctions at (0.2, 0.3, 0.4).
  const std::vector<std::pair<CellType, std::vector<double>>> expected = {
      {CellType::Tet, {0.1, 0.2, 0.3, 0.4}},
      {CellType::Pyramid, {0.336, 0.084, 0.036, 0.144, 0.4}},
      {CellType::Wedge, {0.3, 0.12, 0.18, 0.2, 0.08, 0.12}},
      {CellType::Hex, {0.336, 0.084, 0.036, 0.144, 0.224, 0.056, 0.024, 0.096}}};
  for (const auto& [type, want] : expected) {
    double n[8];
    shapeFunctions(type, {0.2, 0.3, 0.4}, n);
    for (size_t i = 0; i < want.size(); ++i)
      EXPECT_NEAR(n[i], want[i], 1e-15) << mesh::cellTypeName(type) << " N" << i;
  }
}

TEST(Interpolation, DerivativesMatchFiniteDifferences) {
  const glm::dvec3 q(0.23, 0.31, 0.37);
  const double h = 1e-6;
  for (CellType type : mesh::kAllCellTypes) {
    double d[3][8], plus[8], minus[8];
    shapeDerivatives(type, q, d[0], d[1], d[2]);
    for (int axis = 0; axis < 3; ++axis) {
      glm::dvec3 e(0.0);
      e[axis] = h;
      shapeFunctions(type, q + e, plus);
      shapeFunctions(type, q - e, minus);
      for (uint32_t i = 0; i < mesh::numVerts(type); ++i)
        EXPECT_NEAR(d[axis][i], (plus[i] - minus[i]) / (2 * h), 1e-8) << mesh::cellTypeName(type);
    }
  }
}

TEST(Interpolation, ForwardAndInverseMapsMatchVtkOnDistortedCells) {
  for (const VtkCase& c : vtkCases()) {
    for (const VtkPoint& p : c.points) {
      glm::dvec3 x = parametricToWorld(c.type, c.corners, p.rst);
      EXPECT_LT(glm::length(x - p.x), 1e-14) << mesh::cellTypeName(c.type);
      Inversion inv = worldToParametric(c.type, c.corners, p.x);
      EXPECT_TRUE(inv.converged) << mesh::cellTypeName(c.type);
      EXPECT_LT(glm::length(inv.rst - p.rst), 1e-10) << mesh::cellTypeName(c.type);
    }
  }
}

// Random distortion of the reference element: every vertex moved by up to `amount` per axis.
std::vector<glm::dvec3> distorted(CellType type, double amount, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-amount, amount);
  auto corners = test::referenceCorners(type);
  for (auto& c : corners) c += glm::dvec3(u(rng), u(rng), u(rng));
  return corners;
}

// A random point of the parametric domain (away from the pyramid's apex, where r and s are
// undetermined).
glm::dvec3 randomParametric(CellType type, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  glm::dvec3 q(u(rng), u(rng), u(rng));
  if (type == CellType::Tet || type == CellType::Wedge) {
    if (q.x + q.y > 1.0) q.x = 1.0 - q.x, q.y = 1.0 - q.y;
    if (type == CellType::Tet && q.x + q.y + q.z > 1.0) q.z = (1.0 - q.x - q.y) * u(rng);
  }
  if (type == CellType::Pyramid) q.z *= 0.95;
  return q;
}

TEST(Interpolation, NewtonRoundTripOnRandomDistortedElements) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-5.0, 5.0);
  for (CellType type : mesh::kAllCellTypes) {
    for (int e = 0; e < 200; ++e) {
      auto corners = distorted(type, 0.15, rng);
      std::vector<double> v(corners.size());
      for (auto& x : v) x = value(rng);
      for (int k = 0; k < 5; ++k) {
        glm::dvec3 q = randomParametric(type, rng);
        glm::dvec3 p = parametricToWorld(type, corners, q);
        Inversion inv = worldToParametric(type, corners, p);
        ASSERT_TRUE(inv.converged) << mesh::cellTypeName(type) << " element " << e;
        EXPECT_LT(glm::length(inv.rst - q), 1e-9) << mesh::cellTypeName(type);
        double n[8], want = 0.0;
        shapeFunctions(type, q, n);
        for (size_t i = 0; i < v.size(); ++i) want += n[i] * v[i];
        EXPECT_NEAR(interpolate(type, corners, v, p), want, 1e-9) << mesh::cellTypeName(type);
      }
    }
  }
}

// Affine images of the reference elements reproduce linear fields exactly, wherever they sit.
void checkLinearFields(const glm::dvec3& offset, double tolerance) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (CellType type : mesh::kAllCellTypes) {
    for (int e = 0; e < 50; ++e) {
      glm::dmat3 a(1.0);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) a[i][j] += 0.4 * u(rng);
      if (glm::determinant(a) < 0.1) continue;  // keep the element well shaped
      const glm::dvec3 g(u(rng), u(rng), u(rng));
      const double g0 = 3.0 * u(rng);
      auto field = [&](const glm::dvec3& x) { return g0 + glm::dot(g, x - offset); };
      std::vector<glm::dvec3> corners;
      std::vector<double> v;
      for (const auto& c : test::referenceCorners(type)) {
        corners.push_back(offset + a * c);
        v.push_back(field(corners.back()));
      }
      for (int k = 0; k < 10; ++k) {
        glm::dvec3 p = parametricToWorld(type, corners, randomParametric(type, rng));
        EXPECT_NEAR(interpolate(type, corners, v, p), field(p), tolerance)
            << mesh::cellTypeName(type);
      }
    }
  }
}

TEST(Interpolation, LinearFieldsAreExactOnAffineElements) {
  checkLinearFields({0, 0, 0}, 1e-13);
}

TEST(Interpolation, LinearFieldsAreExactFarFromTheOrigin) {
  checkLinearFields({1e6, -2e6, 5e5}, 1e-9);
}

TEST(Interpolation, PointsOutsideTheDomainAreClamped) {
  // Trilinear field on the unit cube: outside, the value of the nearest face point.
  auto hex = test::referenceCorners(CellType::Hex);
  std::vector<double> v;
  for (const auto& c : hex) v.push_back(1.0 + c.x * c.y + 2.0 * c.z);
  EXPECT_NEAR(interpolate(CellType::Hex, hex, v, {1.002, 0.5, 0.25}), 1.0 + 0.5 + 0.5, 1e-12);
  EXPECT_NEAR(interpolate(CellType::Hex, hex, v, {0.3, -0.001, 1.001}), 3.0, 1e-12);
  // Wedge: beyond the slanted face r + s = 1, onto it.
  auto wedge = test::referenceCorners(CellType::Wedge);
  std::vector<double> w;
  for (const auto& c : wedge) w.push_back(c.x + 10.0 * c.y);
  EXPECT_NEAR(interpolate(CellType::Wedge, wedge, w, {0.2505, 0.7505, 0.5}), 0.25 + 7.5, 1e-9);
}

TEST(Interpolation, VerticesApexAndDegenerateElements) {
  for (CellType type : mesh::kAllCellTypes) {
    auto corners = test::referenceCorners(type);
    std::vector<double> v;
    for (size_t i = 0; i < corners.size(); ++i) v.push_back(double(i * i) - 3.0);
    for (size_t i = 0; i < corners.size(); ++i)
      EXPECT_NEAR(interpolate(type, corners, v, corners[i]), v[i], 1e-9)
          << mesh::cellTypeName(type) << " vertex " << i;
  }
  // Flat elements have no inverse map: the answer is finite, not NaN.
  std::vector<glm::dvec3> flatTet = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  const std::vector<double> tv = {1, 2, 3, 4};
  EXPECT_TRUE(std::isfinite(interpolate(CellType::Tet, flatTet, tv, {0.2, 0.2, 0})));
  auto flatHex = test::referenceCorners(CellType::Hex);
  for (auto& c : flatHex) c.z = 0.0;
  std::vector<double> hv = {1, 2, 3, 4, 5, 6, 7, 8};
  EXPECT_TRUE(std::isfinite(interpolate(CellType::Hex, flatHex, hv, {0.5, 0.5, 0.0})));
  EXPECT_TRUE(std::isfinite(interpolate(CellType::Hex, flatHex, hv, {0.5, 0.5, 0.5})));
  // A NaN vertex value poisons the element (a transparent sample downstream).
  hv[3] = NAN;
  EXPECT_TRUE(std::isnan(
      interpolate(CellType::Hex, test::referenceCorners(CellType::Hex), hv, {0.5, 0.5, 0.5})));
}

}  // namespace
}  // namespace sm::ref
