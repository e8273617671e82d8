// Control points as VTK evaluates them (scene/control_points.h) and the colour spaces
// (scene/color_space.h): known answers. vtk_peers_test.py compares with VTK itself.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "scene/control_points.h"

namespace sm::scene {
namespace {

constexpr double kTol = 1e-12;

std::vector<OpacityNode> ramp(double midpoint, double sharpness) {
  return {{2.0, 0.2, midpoint, sharpness}, {6.0, 1.0}};
}

TEST(ControlPoints, MidpointOneHalfAndNoSharpnessIsLinear) {
  const auto nodes = ramp(0.5, 0.0);
  for (int i = 0; i <= 40; ++i) {
    const double x = 2.0 + 4.0 * i / 40.0;
    EXPECT_NEAR(evaluateOpacity(nodes, x), 0.2 + 0.8 * (x - 2.0) / 4.0, kTol) << x;
  }
}

TEST(ControlPoints, TheValueIsHalfWayAtTheMidpointWhateverTheSharpness) {
  for (double midpoint : {0.1, 0.3, 0.5, 0.9})
    for (double sharpness : {0.0, 0.3, 0.7, 0.98}) {
      const double x = 2.0 + 4.0 * midpoint;
      EXPECT_NEAR(evaluateOpacity(ramp(midpoint, sharpness), x), 0.6, 1e-9)
          << midpoint << " " << sharpness;
    }
}

TEST(ControlPoints, AMidpointMakesTwoLinearPiecesWithoutSharpness) {
  // Midpoint 0.25: half the rise over the first quarter, the other half over the rest.
  const auto nodes = ramp(0.25, 0.0);
  EXPECT_NEAR(evaluateOpacity(nodes, 2.5), 0.2 + 0.4 * 0.5, kTol);
  EXPECT_NEAR(evaluateOpacity(nodes, 4.5), 0.6 + 0.4 * ((4.5 - 3.0) / 3.0), kTol);
}

TEST(ControlPoints, FullSharpnessIsAStepAtTheMidpoint) {
  const auto nodes = ramp(0.3, 1.0);
  EXPECT_EQ(evaluateOpacity(nodes, 3.19), 0.2);
  EXPECT_EQ(evaluateOpacity(nodes, 3.21), 1.0);
}

TEST(ControlPoints, SharpnessFlattensTheEndsAndStaysWithinTheValues) {
  const auto soft = ramp(0.5, 0.0), sharp = ramp(0.5, 0.6);
  double last = 0.0;
  for (int i = 0; i <= 100; ++i) {
    const double x = 2.0 + 4.0 * i / 100.0, v = evaluateOpacity(sharp, x);
    EXPECT_GE(v, 0.2);
    EXPECT_LE(v, 1.0);
    EXPECT_GE(v, last - 1e-15) << "not monotone at " << x;
    last = v;
  }
  // Near the ends it stays closer to the end values than the linear curve does.
  EXPECT_LT(evaluateOpacity(sharp, 2.4), evaluateOpacity(soft, 2.4));
  EXPECT_GT(evaluateOpacity(sharp, 5.6), evaluateOpacity(soft, 5.6));
}

TEST(ControlPoints, OutsideTheNodesTheEndValuesHoldAndEqualXJump) {
  const std::vector<OpacityNode> nodes = {{0.0, 0.0}, {0.5, 0.2}, {0.5, 0.9}, {1.0, 1.0}};
  EXPECT_EQ(evaluateOpacity(nodes, -3.0), 0.0);
  EXPECT_EQ(evaluateOpacity(nodes, 7.0), 1.0);
  EXPECT_NEAR(evaluateOpacity(nodes, 0.25), 0.1, kTol);
  EXPECT_NEAR(evaluateOpacity(nodes, 0.5), 0.2, kTol);  // the first of equal points takes x
  EXPECT_NEAR(evaluateOpacity(nodes, 0.75), 0.95, kTol);
  EXPECT_EQ(evaluateOpacity({}, 0.5), 0.0);
}

TEST(ControlPoints, ColoursFollowTheSameCurvePerComponentInRgb) {
  const std::vector<ColorNode> nodes = {{0.0, {0.0, 1.0, 0.5}, 0.3, 0.4}, {1.0, {1.0, 0.0, 0.5}}};
  const std::vector<OpacityNode> red = {{0.0, 0.0, 0.3, 0.4}, {1.0, 1.0}};
  for (double x : {0.1, 0.3, 0.55, 0.9}) {
    const glm::dvec3 c = evaluateColor(nodes, x, ColorSpace::RGB);
    EXPECT_NEAR(c.r, evaluateOpacity(red, x), kTol);
    EXPECT_NEAR(c.g, 1.0 - evaluateOpacity(red, x), kTol);
    EXPECT_NEAR(c.b, 0.5, kTol);
  }
}

TEST(ControlPoints, StepGivesEachIntervalTheColourOfThePointThatEndsIt) {
  const std::vector<ColorNode> nodes = {{0.0, {1, 0, 0}}, {0.5, {0, 1, 0}}, {1.0, {0, 0, 1}}};
  EXPECT_EQ(evaluateColor(nodes, 0.0, ColorSpace::Step), glm::dvec3(1, 0, 0));
  EXPECT_EQ(evaluateColor(nodes, 0.01, ColorSpace::Step), glm::dvec3(0, 1, 0));
  EXPECT_EQ(evaluateColor(nodes, 0.5, ColorSpace::Step), glm::dvec3(0, 1, 0));
  EXPECT_EQ(evaluateColor(nodes, 0.51, ColorSpace::Step), glm::dvec3(0, 0, 1));
}

TEST(ControlPoints, HsvGoesThroughGreenOrTheShortWayThroughMagenta) {
  const std::vector<ColorNode> nodes = {{0.0, {1, 0, 0}}, {1.0, {0, 0, 1}}};
  const glm::dvec3 plain = evaluateColor(nodes, 0.5, ColorSpace::HSV, false);
  const glm::dvec3 wrapped = evaluateColor(nodes, 0.5, ColorSpace::HSV, true);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(plain[k], glm::dvec3(0, 1, 0)[k], kTol);
    EXPECT_NEAR(wrapped[k], glm::dvec3(1, 0, 1)[k], kTol);
  }
}

TEST(ColorSpaces, ConversionsRoundTrip) {
  // VTK's sRGB matrices are rounded to four decimals, so through XYZ a colour comes back within
  // about 1e-4; HSV is exact.
  for (ColorSpace space : {ColorSpace::Lab, ColorSpace::HSV, ColorSpace::Prolab}) {
    const double tolerance = space == ColorSpace::HSV ? 1e-12 : 1e-4;
    for (const glm::dvec3 c :
         {glm::dvec3(0.2, 0.5, 0.9), glm::dvec3(1, 1, 1), glm::dvec3(0.7, 0.1, 0)}) {
      const glm::dvec3 back = fromSpace(toSpace(c, space), space);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[k], c[k], tolerance) << colorSpaceName(space);
    }
  }
}

TEST(ColorSpaces, ProlabHasWhiteAtLightness100AndMatchesVtksOwnTest) {
  const glm::dvec3 white = xyzToProlab(rgbToXyz(glm::dvec3(1.0)));
  EXPECT_NEAR(white.x, 100.0, 1e-9);
  EXPECT_NEAR(white.y, 0.0, 1e-9);
  EXPECT_NEAR(white.z, 0.0, 1e-9);
  // VTK 9.2's TestColorTransferFunction: red to blue in Prolab maps 0.5 to bytes (199, 0, 175).
  const glm::dvec3 c = interpolateColor({1, 0, 0}, {0, 0, 1}, 0.5, ColorSpace::Prolab);
  EXPECT_EQ(int(c.r * 255.0 + 0.5), 199);
  EXPECT_EQ(int(c.g * 255.0 + 0.5), 0);
  EXPECT_EQ(int(c.b * 255.0 + 0.5), 175);
}

// Distance in XYZ of the colour at f from the straight segment between the ends' XYZ, and where
// along it the colour falls.
std::pair<double, double> offTheLine(const glm::dvec3& a, const glm::dvec3& b, double f,
                                     ColorSpace space) {
  const glm::dvec3 xa = rgbToXyz(a), xb = rgbToXyz(b);
  const glm::dvec3 x = rgbToXyz(interpolateColor(a, b, f, space));
  const double t = glm::dot(x - xa, xb - xa) / glm::dot(xb - xa, xb - xa);
  const glm::dvec3 off = x - (xa + t * (xb - xa));
  return {std::sqrt(glm::dot(off, off)), t};
}

TEST(ColorSpaces, ProlabInterpolatesAlongTheStraightLineInXyz) {
  // A projective map sends lines to lines: every colour between two in-gamut ends lies on the
  // segment between them in XYZ (ProLab only reparametrises it; 1e-4: the rounded matrices).
  // Lab, not projective, leaves the line.
  const glm::dvec3 a(0.9, 0.6, 0.1), b(0.1, 0.3, 0.8);
  for (double f : {0.2, 0.5, 0.8}) {
    const auto [off, t] = offTheLine(a, b, f, ColorSpace::Prolab);
    EXPECT_LT(off, 1e-4) << f;
    EXPECT_GT(t, 0.0);
    EXPECT_LT(t, 1.0);
    EXPECT_NE(t, f);  // not XYZ's own parametrisation
    EXPECT_GT(offTheLine(a, b, f, ColorSpace::Lab).first, 1e-2) << f;
  }
}

TEST(ColorSpaces, OutOfGamutColoursAreScaledByTheirLargestComponent) {
  // XYZ (0.9, 0.2, 0.1) is far outside sRGB: VTK divides by the largest component, then clips
  // negatives (vtkMath::XYZToRGB gives (1, 0, 0.248052)).
  const glm::dvec3 c = xyzToRgb({0.9, 0.2, 0.1});
  EXPECT_NEAR(c.r, 1.0, 1e-12);
  EXPECT_EQ(c.g, 0.0);
  EXPECT_NEAR(c.b, 0.2480519093612663, 1e-9);
}

TEST(ColorSpaces, NamesAsParaViewWritesThem) {
  EXPECT_EQ(parseColorSpace("Step", "m.json"), ColorSpace::Step);
  EXPECT_EQ(parseColorSpace("Prolab", "m.json"), ColorSpace::Prolab);
  EXPECT_EQ(parseColorSpace("CIELAB", "m.json"), ColorSpace::Lab);
  EXPECT_EQ(parseColorSpace("diverging", "m.json"), ColorSpace::Diverging);
  try {
    parseColorSpace("CIECAM02", "m.json");
    FAIL() << "accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("m.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'CIECAM02'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sm::scene
