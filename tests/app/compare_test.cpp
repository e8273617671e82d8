// Image checks (app/image_check.h, `shellmarch compare`): per-channel max, RMSE and PSNR and the
// share of pixels beyond the tolerance against values worked out by hand on tiny images, the
// --max-share boundary, non-finite values, and refused input (different sizes, unreadable and
// truncated files). The command line and `render --compare` are tested by compare_test.sh.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>

#include "cli/commands.h"
#include "cli/image_check.h"
#include "common/file_util.h"
#include "scene/image.h"
#include "support/test_support.h"

namespace sm::app {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A 4x2 opaque image of 8-bit levels (10, 20, 30); `changed` sets pixel (0,0) to R 13 and pixel
// (1,1) to G 24: R differs by 3 in one pixel of 8, G by 4 in another.
CheckImage levels(bool changed) {
  CheckImage in;
  in.path = changed ? "b.png" : "a.png";
  in.eightBit = true;
  in.image = scene::Image(4, 2);
  for (auto& p : in.image.pixels) p = glm::vec4(10, 20, 30, 255) / 255.0f;
  if (changed) {
    in.image.at(0, 0).r = 13 / 255.0f;
    in.image.at(1, 1).g = 24 / 255.0f;
  }
  return in;
}

TEST(ImageCheck, IdenticalImagesPassWithInfinitePsnr) {
  const ImageCheck c = checkImages(levels(false), levels(false), {});
  EXPECT_TRUE(c.passed);
  EXPECT_EQ(c.beyond, 0u);
  EXPECT_EQ(c.pixels, 8u);
  for (const ChannelError& e : c.channels) {
    EXPECT_EQ(e.maxAbs, 0.0);
    EXPECT_EQ(e.rmse, 0.0);
    EXPECT_EQ(e.psnr, kInf);
  }
  EXPECT_EQ(c.all.psnr, kInf);
  EXPECT_FALSE(c.alphaInAll);
}

TEST(ImageCheck, KnownDifferences) {
  const ImageCheck c = checkImages(levels(true), levels(false), {});
  // R: one difference of 3 in 8 pixels; G: one of 4; B and A none.
  EXPECT_EQ(c.channels[0].maxAbs, 3.0);
  EXPECT_DOUBLE_EQ(c.channels[0].rmse, std::sqrt(9.0 / 8.0));
  EXPECT_DOUBLE_EQ(c.channels[0].psnr, 20.0 * std::log10(255.0 / std::sqrt(9.0 / 8.0)));
  EXPECT_EQ(c.channels[1].maxAbs, 4.0);
  EXPECT_DOUBLE_EQ(c.channels[1].rmse, std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(c.channels[1].psnr, 20.0 * std::log10(255.0 / std::sqrt(2.0)));
  EXPECT_EQ(c.channels[2].rmse, 0.0);
  EXPECT_EQ(c.channels[3].psnr, kInf);
  // All: over R, G, B (the images are opaque): 25 over 24 values.
  EXPECT_EQ(c.all.maxAbs, 4.0);
  EXPECT_DOUBLE_EQ(c.all.rmse, std::sqrt(25.0 / 24.0));
  EXPECT_EQ(c.beyond, 2u);
  EXPECT_EQ(c.share(), 0.25);
  EXPECT_FALSE(c.passed);
}

TEST(ImageCheck, ToleranceIsStrictlyMoreThanAndShareIsExact) {
  // A difference equal to the tolerance passes; one above it does not.
  EXPECT_EQ(checkImages(levels(true), levels(false), {3, 0}).beyond, 1u);  // G's 4 only
  EXPECT_EQ(checkImages(levels(true), levels(false), {4, 0}).beyond, 0u);
  EXPECT_TRUE(checkImages(levels(true), levels(false), {4, 0}).passed);
  EXPECT_TRUE(checkImages(levels(true), levels(false), {3, 0.125}).passed);
  EXPECT_FALSE(checkImages(levels(true), levels(false), {3, 0.124}).passed);
  EXPECT_TRUE(checkImages(levels(true), levels(false), {0, 0.25}).passed);
  // 29 of 100 pixels against --max-share 0.29 (0.29 * 100 rounds below 29 in doubles).
  CheckImage a, b;
  a.eightBit = b.eightBit = true;
  a.image = b.image = scene::Image(10, 10);
  for (int i = 0; i < 29; ++i) b.image.pixels[i].r = 1.0f;
  const ImageCheck c = checkImages(a, b, {0.5, 0.29});
  EXPECT_EQ(c.beyond, 29u);
  EXPECT_TRUE(c.passed);
  EXPECT_FALSE(checkImages(a, b, {0.5, 0.28}).passed);
}

TEST(ImageCheck, FloatImagesInLevelsAndAlpha) {
  CheckImage a, b;  // PFM-like: floats, times 255
  a.image = b.image = scene::Image(2, 1);
  a.image.pixels = {{0.5f, 0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 0.0f, 1.0f}};
  b.image.pixels = {{0.25f, 0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 0.0f, 0.5f}};
  const ImageCheck c = checkImages(a, b, {63.75, 0});
  EXPECT_EQ(c.channels[0].maxAbs, 63.75);  // (0.5 - 0.25) * 255
  EXPECT_DOUBLE_EQ(c.channels[0].rmse, 63.75 / std::sqrt(2.0));
  EXPECT_EQ(c.channels[3].maxAbs, 127.5);
  EXPECT_TRUE(c.alphaInAll);  // not opaque: alpha is in the summary
  EXPECT_EQ(c.all.maxAbs, 127.5);
  EXPECT_DOUBLE_EQ(c.all.rmse, std::sqrt((63.75 * 63.75 + 127.5 * 127.5) / 8.0));
  EXPECT_EQ(c.beyond, 1u);  // alpha's 127.5 > 63.75; R's 63.75 is not more
}

TEST(ImageCheck, NonFiniteValuesAreBeyondAnyTolerance) {
  CheckImage a, b;
  a.image = b.image = scene::Image(2, 2);
  a.image.pixels[3].g = std::numeric_limits<float>::quiet_NaN();
  const ImageCheck c = checkImages(a, b, {1000, 0});
  EXPECT_EQ(c.nonFinite, 1u);
  EXPECT_EQ(c.beyond, 1u);
  EXPECT_EQ(c.channels[1].rmse, 0.0);  // the finite values agree
  EXPECT_FALSE(c.passed);
}

std::string usageErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const UsageError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no UsageError";
  return {};
}

TEST(ImageCheck, RefusesOtherSizesAndUnreadableFiles) {
  CheckImage small = levels(false);
  small.image = scene::Image(3, 2);
  EXPECT_NE(usageErrorOf([&] { checkImages(levels(false), small, {}); }).find("different sizes"),
            std::string::npos);
  const std::string dir = test::outputDir("image_check");
  const std::string good = dir + "/good.png", cut = dir + "/cut.png";
  scene::writePng(good, levels(false).image, glm::vec3(0.0f));
  const auto bytes = readFile(good);
  writeBytesAtomically(cut, {bytes.data(), bytes.size() - 20});  // no IEND, part of IDAT
  EXPECT_NE(usageErrorOf([&] { readCheckImage(cut, "RESULT"); }).find(cut), std::string::npos);
  EXPECT_NE(usageErrorOf([&] { readCheckImage(dir + "/none.png", "RESULT"); }).find("none.png"),
            std::string::npos);
  EXPECT_NE(usageErrorOf([&] { readCheckImage(dir + "/x.jpg", "BASELINE"); }).find("BASELINE"),
            std::string::npos);
  std::ofstream(dir + "/bad.pfm") << "PF\n4 2\n-1.0\n";  // no pixels
  EXPECT_NE(usageErrorOf([&] { readCheckImage(dir + "/bad.pfm", "RESULT"); }).find("bad.pfm"),
            std::string::npos);
}

TEST(ImageCheck, WritesDifferenceImageAndJson) {
  const std::string dir = test::outputDir("image_check_files");
  CheckFiles f;
  f.result = dir + "/b.png";
  f.baseline = dir + "/a.png";
  f.json = dir + "/check.json";
  f.tolerance = {3, 0};
  scene::writePng(f.result, levels(true).image, glm::vec3(0.0f));
  scene::writePng(f.baseline, levels(false).image, glm::vec3(0.0f));
  std::ostringstream table;
  const ImageCheck c = runImageCheck(f, table);
  EXPECT_FALSE(c.passed);
  EXPECT_EQ(c.channels[1].maxAbs, 4.0);  // the same numbers through the files
  EXPECT_NE(table.str().find("1 of 8 pixels (12.5%)"), std::string::npos) << table.str();
  EXPECT_NE(table.str().find("inf"), std::string::npos);
  const scene::Image diff = scene::readPng(dir + "/b.diff.png");
  ASSERT_EQ(diff.width, 4);
  ASSERT_EQ(diff.height, 2);
  EXPECT_EQ(diff.at(1, 1), glm::vec4(1, 0, 0, 1));  // beyond: red
  EXPECT_EQ(diff.at(0, 0).r, 1.0f);                 // within but different: yellow
  EXPECT_GT(diff.at(0, 0).g, 0.5f);
  EXPECT_EQ(diff.at(0, 0).b, 0.0f);
  EXPECT_EQ(diff.at(2, 0).r, diff.at(2, 0).b);  // equal: grey
  const auto j = nlohmann::json::parse(readTextFile(f.json));
  EXPECT_EQ(j["beyond"], 1);
  EXPECT_EQ(j["beyond_share"], 0.125);
  EXPECT_EQ(j["channels"]["R"]["max_abs"], 3.0);
  EXPECT_TRUE(j["channels"]["B"]["psnr_db"].is_null());  // infinite
  EXPECT_EQ(j["passed"], false);
  EXPECT_EQ(j["diff"], dir + "/b.diff.png");
}

}  // namespace
}  // namespace sm::app
