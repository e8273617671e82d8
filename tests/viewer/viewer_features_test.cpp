// The headless viewer's features against `shellmarch render`: the colour legend, the cut (x),
// opacity points, resizing without new pipelines, and the reduced frames while the camera moves.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/test_support.h"
#include "viewer_checks.h"
#include "viewer_runner.h"

namespace sm::test {
namespace {

// --legend draws the colour legend into what the viewer shows and saves, as `render --legend`
// draws it (the report's render arguments carry the flag); the l key takes it away again.
TEST(ViewerHeadless, LegendIsRendersLegendAndTheKeyTogglesIt) {
  const std::string dir = outputDir("ViewerHeadless.Legend");
  const std::string mesh = generateTestMesh(dir);
  const std::string view = headlessView(mesh, "160x120");
  const std::string with = dir + "/with.png";
  CommandResult r =
      runCommand(view + "--legend --frames 1 --screenshot " + quote(with), dir, "with");
  expectCleanRun(r);
  nlohmann::json j = lastJson(r.out);
  EXPECT_EQ(j["legend"], true);
  const scene::Image shown = expectMatchesRender(dir, mesh, j, with, "with-render");
  // The legend is there: the screenshot differs from the same view without it, at the right only.
  const std::string plain = dir + "/plain.png";
  nlohmann::json noLegend = j;
  auto& a = noLegend["render_args"];
  const auto flag = std::find(a.begin(), a.end(), "--legend");
  ASSERT_NE(flag, a.end()) << j.dump();
  a.erase(flag);
  r = runCommand(
      shellmarch() + " render " + quote(mesh) + renderArgs(noLegend) + " --out " + quote(plain),
      dir, "plain");
  expectCleanRun(r);
  const scene::Image without = scene::readPng(plain);
  ASSERT_EQ(without.pixels.size(), shown.pixels.size());
  int differ = 0, leftmost = shown.width;
  for (int y = 0; y < shown.height; ++y)
    for (int x = 0; x < shown.width; ++x)
      if (shown.at(x, y) != without.at(x, y)) {
        ++differ;
        leftmost = std::min(leftmost, x);
      }
  EXPECT_GT(differ, 200);
  EXPECT_GE(leftmost, shown.width / 2);

  const std::string off = dir + "/off.png";
  const std::string script = writeFile(dir, "off.txt", "frame\nkey l\nframe\nquit\n");
  r = runCommand(view + "--legend --script " + quote(script) + " --screenshot " + quote(off), dir,
                 "off");
  expectCleanRun(r);
  j = lastJson(r.out);
  EXPECT_EQ(j["legend"], false);
  expectMatchesRender(dir, mesh, j, off, "off-render");
}

// The cut (x, then . to move it): the report's render arguments carry it as --clip, and render
// with them draws the screenshot; it cuts something away; x again removes it.
TEST(ViewerHeadless, TheCutKeyClipsAsRenderDoes) {
  const std::string dir = outputDir("ViewerHeadless.Cut");
  const std::string mesh = generateTestMesh(dir);
  const std::string view = headlessView(mesh, "96x72");
  const std::string cut = dir + "/cut.png", plain = dir + "/plain.png", off = dir + "/off.png";
  CommandResult r = runCommand(view + "--script " +
                                   quote(writeFile(dir, "cut.txt", "key x\nkey .\nframe\nquit\n")) +
                                   " --screenshot " + quote(cut),
                               dir, "cut");
  expectCleanRun(r);
  nlohmann::json j = lastJson(r.out);
  ASSERT_FALSE(j["cut"].is_null()) << j.dump();
  const auto& args = j["render_args"];
  EXPECT_EQ(std::count_if(args.begin(), args.end(),
                          [](const nlohmann::json& a) {
                            return a.get<std::string>().rfind("--clip=", 0) == 0;
                          }),
            1)
      << j.dump();
  const scene::Image shown = expectMatchesRender(dir, mesh, j, cut, "cut-render");
  r = runCommand(view + "--frames 1 --screenshot " + quote(plain), dir, "plain");
  expectCleanRun(r);
  const scene::Image uncut = scene::readPng(plain);
  ASSERT_EQ(uncut.pixels.size(), shown.pixels.size());
  size_t differ = 0;
  for (size_t i = 0; i < shown.pixels.size(); ++i) differ += shown.pixels[i] != uncut.pixels[i];
  EXPECT_GT(differ, shown.pixels.size() / 10);
  r = runCommand(view + "--script " +
                     quote(writeFile(dir, "off.txt", "key x\nframe\nkey x\nframe\nquit\n")) +
                     " --screenshot " + quote(off),
                 dir, "off");
  expectCleanRun(r);
  j = lastJson(r.out);
  EXPECT_TRUE(j["cut"].is_null()) << j.dump();
  EXPECT_EQ(scene::compareImages(uncut, scene::readPng(off)).maxAbs, 0.0);
}

// --opacity's points are values of the first field: shown, its frames are render's with the
// points; another field (f) keeps its colour map's opacity; back on the first, the points again.
TEST(ViewerHeadless, OpacityPointsGoWithTheFirstField) {
  const std::string dir = outputDir("ViewerHeadless.Opacity");
  const std::string mesh = generateTestMesh(dir);
  const std::string view = headlessView(mesh, "64x48") + "--opacity 0.3:0,0.5:1 ";
  auto hasOpacity = [](const nlohmann::json& j) {
    for (const auto& a : j["render_args"])
      if (a.get<std::string>().rfind("--opacity=", 0) == 0) return true;
    return false;
  };
  const std::pair<const char*, bool> sessions[] = {
      {"frame\nquit\n", true},
      {"key f\nframe\nquit\n", false},
      {"key f\nframe\nkey f shift\nframe\nquit\n", true}};
  int n = 0;
  for (const auto& [script, first] : sessions) {
    const std::string tag = "session" + std::to_string(++n), shot = dir + "/" + tag + ".png";
    CommandResult r = runCommand(view + "--script " + quote(writeFile(dir, tag + ".txt", script)) +
                                     " --screenshot " + quote(shot),
                                 dir, tag);
    expectCleanRun(r);
    const nlohmann::json j = lastJson(r.out);
    EXPECT_EQ(j["field"] == "vortex", first) << j.dump();
    EXPECT_EQ(hasOpacity(j), first) << j.dump();
    expectMatchesRender(dir, mesh, j, shot, tag + "-render");
  }
}

// The g key's log scale needs a positive range: on a field whose range is not (linear, 0 .. 1)
// the viewer says so, once however often the key is pressed, and shows it linear as render
// would; on one whose range is (shock), it shows the log scale without a word.
TEST(ViewerHeadless, TheGKeySaysWhenAFieldCannotTakeALogScale) {
  const std::string dir = outputDir("ViewerHeadless.LogKey");
  const std::string mesh = generateTestMesh(dir);
  auto logArg = [](const nlohmann::json& j) {
    for (const auto& a : j["render_args"])
      if (a == "--log-scale") return true;
    return false;
  };
  auto viewOf = [&](const std::string& field) {
    std::string v = headlessView(mesh, "32x24");
    return v.replace(v.find("--field vortex"), 14, "--field " + field);
  };
  auto warnings = [](const std::string& err) {
    int n = 0;
    for (size_t at = err.find("needs a positive one"); at != std::string::npos;
         at = err.find("needs a positive one", at + 1))
      ++n;
    return n;
  };
  const std::string thrice =
      writeFile(dir, "g3.txt", "key g\nframe\nkey g\nframe\nkey g\nframe\nquit\n");
  const std::string shot = dir + "/linear.png";
  CommandResult r =
      runCommand(viewOf("linear") + "--script " + quote(thrice) + " --screenshot " + quote(shot),
                 dir, "linear");
  expectCleanRun(r);
  EXPECT_EQ(warnings(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("field 'linear' has the range 0 .. 1"), std::string::npos) << r.err;
  nlohmann::json j = lastJson(r.out);
  EXPECT_FALSE(logArg(j)) << j.dump();
  expectMatchesRender(dir, mesh, j, shot, "linear-render");

  const std::string once = writeFile(dir, "g1.txt", "key g\nframe\nquit\n");
  r = runCommand(viewOf("shock") + "--script " + quote(once), dir, "shock");
  expectCleanRun(r);
  EXPECT_EQ(warnings(r.err), 0) << r.err;
  EXPECT_TRUE(logArg(lastJson(r.out)));
}

// A resize makes new lists and images, not new pipelines: the session that resizes twice builds
// as many as the one that does not, and its last frame is render's at the new size.
TEST(ViewerHeadless, ResizingBuildsNoPipelines) {
  const std::string dir = outputDir("ViewerHeadless.Resize");
  const std::string mesh = generateTestMesh(dir);
  const std::string view = headlessView(mesh, "64x48");
  const std::string shot = dir + "/resized.png";
  CommandResult r = runCommand(
      view + "--script " + quote(writeFile(dir, "still.txt", "frame 3\nquit\n")), dir, "still");
  expectCleanRun(r);
  const nlohmann::json still = lastJson(r.out);
  r = runCommand(view + "--script " +
                     quote(writeFile(dir, "resize.txt",
                                     "frame\nresize 80 60\nframe\nresize 72 40\nframe\nquit\n")) +
                     " --screenshot " + quote(shot),
                 dir, "resized");
  expectCleanRun(r);
  const nlohmann::json resized = lastJson(r.out);
  EXPECT_EQ(resized["size"], nlohmann::json({72, 40}));
  EXPECT_GT(still["pipelines_built"].get<int>(), 0);
  EXPECT_EQ(resized["pipelines_built"], still["pipelines_built"]);
  expectMatchesRender(dir, mesh, resized, shot, "resized-render");
}

// While the camera moves, frames render at half size; the first frame without motion, a
// screenshot's frame and the last frame are full size (a session that ends moving shows its last
// view once more, full size), so what is saved is always render's image.
TEST(ViewerHeadless, MovingFramesRenderSmallAndTheLastIsFull) {
  const std::string dir = outputDir("ViewerHeadless.Moving");
  const std::string mesh = generateTestMesh(dir);
  const std::string view = headlessView(mesh, "96x72");
  struct Session {
    const char* script;
    const char* extra;
    int frames, reduced;
  };
  const Session sessions[] = {
      {"drag left 30 10 2\nframe\nquit\n", "", 2, 1},  // ends moving: one more, full size
      {"drag left 30 10 2\nframe\nframe\nquit\n", "", 2, 1},
      {"drag left 30 10 2\nframe\nquit\n", "--interactive-scale 1 ", 1, 0},
      {"drag left 30 10 2\nscreenshot \nframe\nquit\n", "", 1, 0},
      {"scroll 2\nframe\nkey up\nframe\nquit\n", "--interactive-scale 3 ", 2, 1}};
  std::vector<scene::Image> shots;
  int n = 0;
  for (const Session& s : sessions) {
    const std::string tag = "moving" + std::to_string(++n), shot = dir + "/" + tag + ".png";
    std::string script = s.script;
    const size_t at = script.find("screenshot \n");
    if (at != std::string::npos) script.replace(at, 12, "screenshot " + shot + "\n");
    CommandResult r =
        runCommand(view + s.extra + "--script " + quote(writeFile(dir, tag + ".txt", script)) +
                       " --screenshot " + quote(shot),
                   dir, tag);
    expectCleanRun(r);
    const nlohmann::json j = lastJson(r.out);
    EXPECT_EQ(j["frames"], s.frames) << tag << " " << j.dump();
    EXPECT_EQ(j["reduced_frames"], s.reduced) << tag << " " << j.dump();
    shots.push_back(expectMatchesRender(dir, mesh, j, shot, tag + "-render"));
  }
  // The same view at the end whether the frames on the way were small or not.
  EXPECT_EQ(shots[0].pixels, shots[1].pixels);
  EXPECT_EQ(shots[0].pixels, shots[2].pixels);
  EXPECT_EQ(shots[0].pixels, shots[3].pixels);
}

}  // namespace
}  // namespace sm::test
