// SettingError: the command line's text as what(), the key and detail apart, and each front end's
// name for the key.
#include <gtest/gtest.h>

#include "common/setting_error.h"
#include "session/setting_names.h"

namespace sm::session {
namespace {

TEST(SettingError, WhatIsTheCommandLinesTextAndTheKeyStaysApart) {
  const SettingError e("colormap", "unknown colour map '", "x", "'");
  EXPECT_STREQ(e.what(), "--colormap: unknown colour map 'x'");
  EXPECT_EQ(e.key(), "colormap");
  EXPECT_EQ(e.detail(), "unknown colour map 'x'");
  EXPECT_EQ(apiMessage(e), "colormap: unknown colour map 'x'");
  EXPECT_EQ(pythonMessage(e), "colormap: unknown colour map 'x'");
  // A value from outside cannot forge a second line.
  EXPECT_STREQ(SettingError("view", "'a\nb'").what(), "--view: 'a\\x0ab'");
}

TEST(SettingError, EachFrontEndNamesTheSettingItsOwnWay) {
  EXPECT_EQ(apiName("step"), "sampleDistance");
  EXPECT_EQ(apiName("clip"), "clipPlanes");
  EXPECT_EQ(apiName("log-scale"), "logScale");
  EXPECT_EQ(apiName("early-termination"), "earlyTermination");
  EXPECT_EQ(apiName("fovy"), "camera.fovyDeg");
  EXPECT_EQ(apiName("size"), "width/height");
  EXPECT_EQ(pythonName("log-scale"), "log_scale");
  EXPECT_EQ(pythonName("size"), "size");
  EXPECT_EQ(apiMessage(SettingError("step", "1e-12 is too fine")),
            "sampleDistance: 1e-12 is too fine");
  EXPECT_EQ(pythonMessage(SettingError("opacity-scale", "-1 is negative")),
            "opacity_scale: -1 is negative");
}

TEST(SettingError, OptionKeysLoseTheirDashes) {
  EXPECT_EQ(optionKey("--colormap"), "colormap");
  EXPECT_EQ(optionKey("-k"), "k");
  EXPECT_EQ(optionKey("size"), "size");
  EXPECT_EQ(optionKey("--"), "");
}

}  // namespace
}  // namespace sm::session
