// ParaView's preset names (`--colormap "Cool to Warm"`): every preset builds, the names ParaView
// users reach for are there, the short names keep working, and an unknown name's error suggests
// the closest ones.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/error.h"
#include "scene/paraview_presets.h"
#include "scene/transfer_function.h"

namespace sm::scene {
namespace {

std::string errorOf(const std::string& name) {
  try {
    makeTransferFunction(name);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

double largestDifference(const TransferFunction& a, const TransferFunction& b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.table.size(); ++i)
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, double(std::abs(a.table[i][k] - b.table[i][k])));
  return worst;
}

TEST(ParaViewPresets, TheMostUsedOnesAreThereUnderParaViewsNames) {
  for (const char* name : {"Cool to Warm",
                           "Cool to Warm (Extended)",
                           "Warm to Cool",
                           "Viridis (matplotlib)",
                           "Inferno (matplotlib)",
                           "Plasma (matplotlib)",
                           "Magma (matplotlib)",
                           "Grayscale",
                           "X Ray",
                           "Jet",
                           "Rainbow Uniform",
                           "Turbo",
                           "Black-Body Radiation",
                           "Blue Orange (divergent)",
                           "Rainbow Desaturated",
                           "Black, Blue and White",
                           "erdc_rainbow_bright",
                           "Blue - Green - Orange",
                           "Yellow - Gray - Blue",
                           "Fast"})
    EXPECT_NE(findParaViewPreset(name), nullptr) << name;
}

TEST(ParaViewPresets, EveryPresetBuildsAFiniteTableFromItsFirstToItsLastColour) {
  ASSERT_GE(paraViewPresetNames().size(), 30u);
  for (const std::string& name : paraViewPresetNames()) {
    const TransferFunction tf = makeTransferFunction(name, 256);
    ASSERT_EQ(tf.table.size(), 256u) << name;
    for (const glm::vec4& e : tf.table)
      for (int k = 0; k < 4; ++k) ASSERT_TRUE(e[k] >= 0.0f && e[k] <= 1.0f) << name;
    EXPECT_EQ(tf.table.front().a, 0.0f) << name;  // no "Points": the opacity ramp
    EXPECT_EQ(tf.table.back().a, 1.0f) << name;
  }
  // The ends are the first and last points' colours.
  const TransferFunction xray = makeTransferFunction("X Ray");
  EXPECT_EQ(glm::vec3(xray.table.front()), glm::vec3(1, 1, 1));
  EXPECT_EQ(glm::vec3(xray.table.back()), glm::vec3(0, 0, 0));
  EXPECT_EQ(makeTransferFunction("Black-Body Radiation").nanColor,
            glm::vec3(0.0f, 0.498039215686f, 1.0f));
}

TEST(ParaViewPresets, CaseIsIgnoredAndShortNamesKeepTheirTables) {
  EXPECT_EQ(makeTransferFunction("cool to warm").table, makeTransferFunction("Cool to Warm").table);
  EXPECT_EQ(makeTransferFunction("X RAY").table, makeTransferFunction("X Ray").table);
  EXPECT_EQ(makeTransferFunction("Viridis").table, makeTransferFunction("viridis").table);
  EXPECT_NE(makeTransferFunction("jet").table, makeTransferFunction("Jet").table);
}

TEST(ParaViewPresets, AgreeWithTheBuiltInTablesOfTheSameMaps) {
  // Independent data: the built-in tables are matplotlib's 256 colours; the presets are control
  // points interpolated here. matplotlib's coolwarm is Moreland's map from blue to red with the
  // white point inserted; ParaView's "Cool to Warm" gives the grey middle point (0.865) itself.
  EXPECT_LT(
      largestDifference(makeTransferFunction("Cool to Warm"), makeTransferFunction("cool-to-warm")),
      0.025);
  EXPECT_LT(largestDifference(makeTransferFunction("Viridis (matplotlib)"),
                              makeTransferFunction("viridis")),
            2e-3);
  EXPECT_LT(largestDifference(makeTransferFunction("Turbo"), makeTransferFunction("turbo")), 2e-3);
}

TEST(ParaViewPresets, AStepPresetIsPiecewiseConstant) {
  // "Traffic Lights Step": red up to 1/3, amber to 2/3, green after.
  const TransferFunction tf = makeTransferFunction("Traffic Lights Step", 301);
  EXPECT_EQ(glm::vec3(tf.table[50]), glm::vec3(1, 0, 0));
  EXPECT_EQ(glm::vec3(tf.table[150]), glm::vec3(1, 0.862745f, 0));
  EXPECT_EQ(glm::vec3(tf.table[250]), glm::vec3(0, 0.695201f, 0));
  EXPECT_EQ(glm::vec3(tf.table[250]), glm::vec3(tf.table[201]));
}

TEST(ParaViewPresets, AnUnknownNameIsAOneLineErrorWithTheClosestNames) {
  const std::string e = errorOf("Cool to Wram");
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  EXPECT_NE(e.find("--colormap: unknown colour map 'Cool to Wram' (closest: 'Cool to Warm'"),
            std::string::npos)
      << e;
  EXPECT_NE(errorOf("inferno (matplotib)").find("'Inferno (matplotlib)'"), std::string::npos);
  EXPECT_NE(errorOf("magma").find("'Magma (matplotlib)'"), std::string::npos);
  // Nothing close: no suggestions, still the way out.
  const std::string far = errorOf("qqqqqqqqqqqqqqqqqqqq");
  EXPECT_EQ(far.find("closest"), std::string::npos) << far;
  EXPECT_NE(far.find("ParaView .json file"), std::string::npos) << far;
}

TEST(ParaViewPresets, ClosestNamesRankByEditDistance) {
  const std::vector<std::string> names = {"Jet", "Turbo", "X Ray", "Grayscale"};
  EXPECT_EQ(closestNames("jett", names, 1), std::vector<std::string>{"Jet"});
  EXPECT_EQ(closestNames("greyscale", names, 1), std::vector<std::string>{"Grayscale"});
  EXPECT_TRUE(closestNames("zzzzzzzzzzzz", names).empty());
}

}  // namespace
}  // namespace sm::scene
