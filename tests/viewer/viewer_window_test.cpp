// The viewer end to end, as a user runs it: a window under Xvfb (xvfb-run), driven by a script,
// compared with `shellmarch render` at the camera the viewer ends with; what reaches the screen
// (Xvfb's framebuffer) compared with the screenshot; headless use without a display.
// Every run has the validation layer on (SHELLMARCH_VALIDATION=1 from ctest) and must report
// no error.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <thread>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "common/file_util.h"
#include "support/test_support.h"
#include "viewer_runner.h"

namespace sm::test {
namespace {

const glm::vec3 kBackground{0.1f, 0.1f, 0.12f};  // render's and view's default

// Orbit, zoom (wheel and drag), pan, a time step, opacity, sampling and colour map, after a
// resize: everything the state carries, so that a mismatch with render shows.
const char* kScript =
    "resize 176 132\n"
    "frame 2\n"
    "drag left 60 20 4       # orbit\n"
    "frame\n"
    "scroll 2                # zoom in\n"
    "drag right 0 -12        # and a little more\n"
    "frame\n"
    "drag middle 10 -6 2     # pan\n"
    "key right               # next time step\n"
    "frame\n"
    "key up                  # more opaque\n"
    "key ]                   # coarser sampling\n"
    "key c                   # next colour map\n"
    "frame 2\n"
    "quit\n";

std::string writeScript(const std::string& dir) {
  return writeFile(dir, "session.txt", kScript);
}

void expectCleanRun(const CommandResult& r) {
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("validation error"), std::string::npos) << r.err;
}

// The scripted state arrived: sizes, step, settings and a camera moved in all three ways.
void expectScriptedState(const nlohmann::json& j) {
  EXPECT_EQ(j["frames"], 7);
  EXPECT_EQ(j["presented"], 7);
  EXPECT_EQ(j["size"], nlohmann::json({176, 132}));
  EXPECT_EQ(j["time"], 1);
  EXPECT_EQ(j["field"], "vortex");
  EXPECT_NE(j["colormap"], "viridis");
  EXPECT_DOUBLE_EQ(j["opacity_scale"].get<double>(), 1.25);
  EXPECT_GE(j["swapchain_rebuilds"].get<int>(), 1);  // the resize outdated the swapchain
  EXPECT_EQ(j["validation_errors"], 0);
  EXPECT_EQ(j["geometry_builds"], 1);  // the time step uploaded scalars only
  EXPECT_EQ(j["scalar_uploads"], 2);
  auto v = [&](const char* k, const nlohmann::json& o) {
    return glm::dvec3(o[k][0].get<double>(), o[k][1].get<double>(), o[k][2].get<double>());
  };
  const glm::dvec3 eye = v("eye", j), at = v("at", j), homeEye = v("eye", j["home"]),
                   homeAt = v("at", j["home"]);
  EXPECT_LT(glm::length(eye - at), 0.9 * glm::length(homeEye - homeAt));      // zoomed in
  EXPECT_GT(glm::length(at - homeAt), 1e-3 * glm::length(homeEye - homeAt));  // panned
  EXPECT_LT(glm::dot(glm::normalize(eye - at), glm::normalize(homeEye - homeAt)), 0.99);  // orbited
}

// The screenshot equals `shellmarch render` at the viewer's final camera, step and settings (the
// report's render_args); `tag` names the files. Returns the screenshot.
scene::Image expectMatchesRender(const std::string& dir, const std::string& mesh,
                                 const nlohmann::json& j, const std::string& shot,
                                 const std::string& tag = "render") {
  const std::string out = dir + "/" + tag + ".png";
  CommandResult r = runCommand(
      shellmarch() + " render " + quote(mesh) + renderArgs(j) + " --out " + quote(out), dir, tag);
  expectCleanRun(r);
  scene::Image view = scene::readPng(shot);
  const scene::ImageError e = scene::compareImages(view, scene::readPng(out));
  std::printf("%s: viewer screenshot vs render: RMSE %.3g, max abs %.3g (8-bit steps %.1f)\n",
              tag.c_str(), e.rmse, e.maxAbs, e.maxAbs * 255);
  EXPECT_LE(e.maxAbs, 1.0 / 255 + 1e-6) << tag;
  return view;
}

// The scripted session's screenshot: render's image at the scripted size, not blank.
void expectScriptedShotMatchesRender(const std::string& dir, const std::string& mesh,
                                     const nlohmann::json& j, const std::string& shot) {
  const scene::Image view = expectMatchesRender(dir, mesh, j, shot);
  ASSERT_EQ(view.width, 176);
  ASSERT_EQ(view.height, 132);
  EXPECT_GT(pixelsUnlike(view, kBackground), size_t(view.width * view.height / 10));
}

TEST(ViewerWindow, ScriptedSessionUnderXvfbMatchesRender) {
  const std::string dir = outputDir("ViewerWindow.Scripted");
  const std::string mesh = generateTestMesh(dir), shot = dir + "/view.png";
  CommandResult r =
      runCommand(xvfbRun() + " " + shellmarch() + " view " + quote(mesh) +
                     " --field vortex --size 160x120 --frames 50 --script " +
                     quote(writeScript(dir)) + " --screenshot " + quote(shot) + " --print-camera",
                 dir, "view");
  expectCleanRun(r);
  const nlohmann::json j = lastJson(r.out);
  expectScriptedState(j);
  expectScriptedShotMatchesRender(dir, mesh, j, shot);
}

TEST(ViewerHeadless, HeadlessSurfaceWithoutADisplayMatchesRender) {
  const std::string dir = outputDir("ViewerHeadless.Scripted");
  const std::string mesh = generateTestMesh(dir), shot = dir + "/view.png";
  CommandResult r =
      runCommand("env -u DISPLAY -u WAYLAND_DISPLAY " + shellmarch() + " view " + quote(mesh) +
                     " --field vortex --size 160x120 --headless --script " +
                     quote(writeScript(dir)) + " --screenshot " + quote(shot) + " --print-camera",
                 dir, "view");
  expectCleanRun(r);
  const nlohmann::json j = lastJson(r.out);
  expectScriptedState(j);
  expectScriptedShotMatchesRender(dir, mesh, j, shot);
}

// "Finer step" pressed without end stops at a hundredth of the starting step: frames stay
// interactive, and the step never reaches what float positions along a ray cannot resolve.
TEST(ViewerHeadless, FinerStepStopsAtAHundredthOfTheStart) {
  const std::string dir = outputDir("ViewerHeadless.FinerStep");
  const std::string mesh = generateTestMesh(dir);
  std::string finer = "frame\n";
  for (int i = 0; i < 40; ++i) finer += "key [\n";  // 1.25^40: about 7500 times finer
  const std::string script = writeFile(dir, "finer.txt", finer + "frame\nquit\n");
  auto run = [&](const std::string& extra, const char* name) {
    CommandResult r =
        runCommand("env -u DISPLAY -u WAYLAND_DISPLAY " + shellmarch() + " view " + quote(mesh) +
                       " --field vortex --size 32x24 --headless" + extra + " --print-camera",
                   dir, name);
    expectCleanRun(r);
    return lastJson(r.out)["step"].get<double>();
  };
  const double start = run(" --frames 1", "start");
  const double finest = run(" --script " + quote(script), "finer");
  EXPECT_NEAR(finest, start / 100, 1e-9 * start);
}

// Breaks the zlib stream of point array `array` in a .vtu written by `shellmarch generate`
// (appended raw data, one block, UInt64 block header): its header stays readable, its values
// do not.
void corruptArray(const std::string& vtu, const std::string& array) {
  std::vector<uint8_t> bytes = readFile(vtu);
  const std::string text(bytes.begin(), bytes.end());
  const size_t name = text.find("Name=\"" + array + "\"");
  ASSERT_NE(name, std::string::npos);
  const size_t offset = std::stoull(text.substr(text.find("offset=\"", name) + 8));
  const size_t data = text.find('_', text.find("<AppendedData")) + 1;
  const size_t stream = data + offset + 4 * 8;  // past the block count, sizes and one block size
  ASSERT_EQ(bytes.at(stream), 0x78);            // zlib's header
  bytes[stream] = bytes[stream + 1] = 0;
  writeBytesAtomically(vtu, bytes);
}

// A time series holds one step per field in memory, as `render --time all` does: a step is read
// from the file when it is shown (and once each for the range over all steps, unless --range
// gives it). A step whose data is corrupt therefore stops the viewer only when it is read: with
// --range, when it is shown; without, when the range is taken, before the first frame. (Read
// whole at load, as before, it stopped every session of the file.)
TEST(ViewerHeadless, StepsAreReadFromTheFileWhenShown) {
  const std::string dir = outputDir("ViewerHeadless.StepsWhenShown");
  const std::string mesh = generateTestMesh(dir);
  const std::string script =
      writeFile(dir, "steps.txt", "frame\nkey right\nframe\nkey right\nframe\nquit\n");
  corruptArray(dir + "/cube/cube_0.vtu", "vortex@t2");
  const std::string view = "env -u DISPLAY -u WAYLAND_DISPLAY " + shellmarch() + " view " +
                           quote(mesh) + " --field vortex --size 32x24 --headless ";
  CommandResult first = runCommand(view + "--range 0,1 --frames 1 --print-camera", dir, "first");
  expectCleanRun(first);
  EXPECT_EQ(lastJson(first.out)["time"], 0);
  const std::string want =
      "shellmarch: error: " + dir +
      "/cube/cube_0.vtu: point array 'vortex@t2': compressed block 0 is corrupt (zlib: data "
      "error)\n";
  CommandResult stepped =
      runCommand(view + "--range 0,1 --script " + quote(script) + " --print-camera", dir, "step");
  EXPECT_EQ(stepped.status, 1);
  EXPECT_EQ(stepped.err, want);
  CommandResult ranged = runCommand(view + "--frames 1", dir, "range");
  EXPECT_EQ(ranged.status, 1);
  EXPECT_EQ(ranged.err, want);
}

// `shellmarch view MESH --field vortex --size WxH --headless --print-camera `, without a display:
// the start of every headless session below.
std::string headlessView(const std::string& mesh, const char* size) {
  return "env -u DISPLAY -u WAYLAND_DISPLAY " + shellmarch() + " view " + quote(mesh) +
         " --field vortex --size " + size + " --headless --print-camera ";
}

// Playing shows a step a frame, each read and uploaded on a thread while the frame before
// renders; a step the user skips while it is read ahead is dropped, its read error with it
// (step 2 of the test series is corrupt), and a step shown is read or fails as before.
TEST(ViewerHeadless, PlayShowsAStepAFrameReadAhead) {
  const std::string dir = outputDir("ViewerHeadless.Play");
  const std::string mesh = generateTestMesh(dir);
  const std::string view = headlessView(mesh, "32x24");
  // Steps 0 1 2 0 1: four of the five frames find their step read ahead.
  const std::string played = dir + "/played.png";
  CommandResult r =
      runCommand(view + "--play --frames 5 --screenshot " + quote(played), dir, "play");
  expectCleanRun(r);
  nlohmann::json j = lastJson(r.out);
  EXPECT_EQ(j["playing"], true);
  EXPECT_EQ(j["prefetched_steps"], 4);
  EXPECT_EQ(j["time"], 1);
  expectMatchesRender(dir, mesh, j, played, "played-render");

  corruptArray(dir + "/cube/cube_0.vtu", "vortex@t2");
  // Space starts playing (step 0, then 1 while 2 is read ahead and fails), left goes back to 0
  // (the read of 2 is dropped), space pauses on 0.
  const std::string back = dir + "/back.png";
  const std::string skip = writeFile(dir, "skip.txt",
                                     "key space\nframe 2\nkey left\nframe\nkey space\nframe\n"
                                     "quit\n");
  r = runCommand(view + "--range 0,1 --script " + quote(skip) + " --screenshot " + quote(back), dir,
                 "skip");
  expectCleanRun(r);
  j = lastJson(r.out);
  EXPECT_EQ(j["playing"], false);
  EXPECT_EQ(j["prefetched_steps"], 1);
  EXPECT_EQ(j["time"], 0);
  expectMatchesRender(dir, mesh, j, back, "back-render");

  const std::string on = writeFile(dir, "on.txt", "key space\nframe 3\nquit\n");
  r = runCommand(view + "--range 0,1 --script " + quote(on), dir, "shown");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "shellmarch: error: " + dir +
                       "/cube/cube_0.vtu: point array 'vortex@t2': compressed block 0 is corrupt "
                       "(zlib: data error)\n");
}

// --fps holds each played step on screen for 1/F s at least (the viewer measures how long each
// was shown, on the clock it paces by); input still acts at every frame, and without --fps play
// never waits.
TEST(ViewerHeadless, FpsHoldsEachPlayedStep) {
  const std::string dir = outputDir("ViewerHeadless.Fps");
  const std::string mesh = generateTestMesh(dir);
  const std::string view = headlessView(mesh, "32x24");
  CommandResult r = runCommand(view + "--play --frames 5 --fps 4", dir, "capped");
  expectCleanRun(r);
  nlohmann::json j = lastJson(r.out);
  EXPECT_EQ(j["time"], 1);  // steps 0 1 2 0 1
  EXPECT_EQ(j["fps_cap"], 4.0);
  ASSERT_TRUE(j["shortest_played_step_ms"].is_number()) << j.dump();
  EXPECT_GE(j["shortest_played_step_ms"].get<double>(), 250.0 - 1e-6);
  EXPECT_GT(j["pace_wait_ms"].get<double>(), 0.0);

  // Space pauses between held steps: the step shown stays.
  const std::string pause = writeFile(dir, "pause.txt", "frame 3\nkey space\nframe 3\nquit\n");
  r = runCommand(view + "--play --fps 8 --script " + quote(pause), dir, "paused");
  expectCleanRun(r);
  j = lastJson(r.out);
  EXPECT_EQ(j["playing"], false);
  EXPECT_EQ(j["time"], 2);  // frames 1 and 2 advanced to step 2; paused before frame 3 moved on
  EXPECT_GE(j["shortest_played_step_ms"].get<double>(), 125.0 - 1e-6);

  r = runCommand(view + "--play --frames 4", dir, "uncapped");
  expectCleanRun(r);
  j = lastJson(r.out);
  EXPECT_EQ(j["fps_cap"], 0.0);
  EXPECT_EQ(j["pace_wait_ms"], 0.0);
  EXPECT_EQ(j["time"], 0);  // steps 0 1 2 0
}

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

TEST(ViewerHeadless, NoDisplayIsAOneLineError) {
  const std::string dir = outputDir("ViewerHeadless.NoDisplay");
  CommandResult r = runCommand("env -u DISPLAY -u WAYLAND_DISPLAY " + shellmarch() + " view " +
                                   quote(dir + "/not-read-before-the-window.vtu") + " --frames 1",
                               dir, "view");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err,
            "shellmarch: error: view: no display (DISPLAY is not set): run under xvfb-run, or use "
            "--headless\n");
}

TEST(ViewerHeadless, BadInputIsOneLineNamingTheOption) {
  const std::string dir = outputDir("ViewerHeadless.BadInput");
  const std::string mesh = generateTestMesh(dir);
  const std::string script = writeFile(dir, "bad.txt", "frame\ndrag sideways 3 4\n");
  const std::pair<std::string, std::string> cases[] = {
      {"--headless", "--headless needs --frames or --script"},
      {"--headless --script " + quote(script), "bad.txt:2: 'drag' needs a button"},
      {"--headless --frames 1 --time 99", "--time: field 'linear' has 3 time steps"},
      {"--headless --frames 1 --time all", "--time: 'all' is not a step index"},
      {"--headless --frames -2", "--frames"},
      {"--headless --frames 1 --size 0x4", "--size"},
      {"--headless --frames 1 --play --fps 0", "--fps: 0 is not a positive number"},
      {"--headless --frames 1 --play --fps -2", "--fps: -2 is not a positive number"},
      {"--headless --frames 1 --play --fps nan", "--fps: nan is not a positive number"},
      {"--headless --frames 1 --interactive-scale 0", "--interactive-scale: 0 is not in 1 .. 16"},
  };
  for (const auto& [args, want] : cases) {
    CommandResult r = runCommand(shellmarch() + " view " + quote(mesh) + " " + args, dir, "view");
    EXPECT_EQ(r.status, 1) << args;
    EXPECT_NE(r.err.find(want), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
}

}  // namespace
}  // namespace sm::test
