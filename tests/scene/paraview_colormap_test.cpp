// ParaView colour-map JSON (`--colormap FILE.json[:NAME]`, scene::parseParaViewColormap): known
// table entries, preset files of several maps, and one-line errors.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "common/error.h"
#include "scene/transfer_function.h"

namespace sm::scene {
namespace {

// Black to white, and a second map, red to blue, with opacity points.
const std::string kGray =
    R"({"Name": "gray", "ColorSpace": "RGB", "RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1]})";
const std::string kRedBlue =
    R"({"Name": "red-blue", "RGBPoints": [-1, 1, 0, 0, 1, 0, 0, 1],
        "Points": [-1, 0, 0.5, 0, 1, 0.5, 0.5, 0]})";

std::string errorOf(const std::string& text, const std::string& preset = "") {
  try {
    parseParaViewColormap(text, "m.json", 257, preset);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ParaViewColormap, ControlPointsAreInterpolatedOverTheTable) {
  TransferFunction tf = parseParaViewColormap(kRedBlue, "m.json", 257);
  ASSERT_EQ(tf.table.size(), 257u);
  EXPECT_EQ(tf.table[0], glm::vec4(1, 0, 0, 0));
  EXPECT_EQ(tf.table[256], glm::vec4(0, 0, 1, 0.5f));
  EXPECT_FLOAT_EQ(tf.table[128].r, 0.5f);  // half way in RGB
  EXPECT_FLOAT_EQ(tf.table[128].a, 0.25f);
  // Without "Points" the opacity is a ramp.
  TransferFunction gray = parseParaViewColormap(kGray, "m.json", 257);
  EXPECT_FLOAT_EQ(gray.table[64].a, 0.25f);
  EXPECT_FLOAT_EQ(gray.table[64].g, 0.25f);
}

// NaN takes the map's NanColor at its NanOpacity; without NanOpacity it stays transparent.
TEST(ParaViewColormap, NanColorAndNanOpacity) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  TransferFunction plain = parseParaViewColormap(
      R"({"RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1], "NanColor": [0, 0, 1]})", "m.json", 16);
  EXPECT_EQ(plain.lookup(nan), glm::dvec4(0, 0, 1, 0));
  TransferFunction seen = parseParaViewColormap(
      R"({"RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1], "NanColor": [0, 1, 0], "NanOpacity": 0.25})",
      "m.json", 16);
  EXPECT_EQ(seen.lookup(nan), glm::dvec4(0, 1, 0, 0.25));
  EXPECT_EQ(seen.lookup(std::numeric_limits<double>::infinity()), glm::dvec4(0, 1, 0, 0.25));
  seen.unitDistance = 0.5;
  EXPECT_DOUBLE_EQ(seen.extinction(nan), 0.5);
  EXPECT_EQ(seen.lookup(1.0), glm::dvec4(1, 1, 1, 1));  // finite values are the table's
  EXPECT_NE(errorOf(R"({"RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1], "NanOpacity": 2})")
                .find("\"NanOpacity\" 2 is not in [0, 1]"),
            std::string::npos);
  EXPECT_NE(errorOf(R"({"RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1], "NanOpacity": [1]})")
                .find("\"NanOpacity\" is not a number"),
            std::string::npos);
}

TEST(ParaViewColormap, APresetFileGivesTheMapItNamesOrTheFirstWithAWarning) {
  const std::string both = "[" + kGray + ", " + kRedBlue + "]";
  testing::internal::CaptureStderr();
  TransferFunction first = parseParaViewColormap(both, "m.json", 257);
  const std::string warned = testing::internal::GetCapturedStderr();
  EXPECT_NE(warned.find("m.json: holds 2 colour maps ('gray', 'red-blue'); rendering the first; "
                        "name one as m.json:NAME"),
            std::string::npos)
      << warned;
  // Once per file in a run: an in-situ caller rebuilds its transfer function every frame.
  testing::internal::CaptureStderr();
  parseParaViewColormap(both, "m.json", 257);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  EXPECT_EQ(first.table[256], glm::vec4(1, 1, 1, 1));
  TransferFunction named = parseParaViewColormap(both, "m.json", 257, "red-blue");
  EXPECT_EQ(named.table[0], glm::vec4(1, 0, 0, 0));
  // One map alone warns of nothing, and may be named too.
  testing::internal::CaptureStderr();
  parseParaViewColormap("[" + kGray + "]", "m.json", 257);
  parseParaViewColormap(kGray, "m.json", 257, "gray");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  EXPECT_EQ(errorOf(both, "viridis"),
            "m.json: has no colour map named 'viridis' (it holds 'gray', 'red-blue')");
}

TEST(ParaViewColormap, BadMapsAreOneLineErrors) {
  EXPECT_EQ(
      errorOf(R"({"RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1], "Points": [0, 0, 0.5, 0, 1, 2, 0.5, 0]})"),
      "m.json: \"Points\": opacity 2 of point 2 is outside [0, 1]");
  EXPECT_EQ(errorOf(R"({"RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1], "Points": [0, -0.5, 0.5, 0]})"),
            "m.json: \"Points\": opacity -0.5 of point 1 is outside [0, 1]");
  EXPECT_EQ(errorOf("[]"), "m.json: empty colour-map array");
  EXPECT_EQ(errorOf(R"({"RGBPoints": [0, 0, 0, 0]})"),
            "m.json: \"RGBPoints\" needs at least two (x, r, g, b) points");
  EXPECT_NE(errorOf("{").find("m.json: not valid JSON"), std::string::npos);
}

}  // namespace
}  // namespace sm::scene
