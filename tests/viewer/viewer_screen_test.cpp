// What reaches the screen, and what ranks agree on. Xvfb -fbdir keeps its screen in a file, so the
// test can read the window's pixels while the viewer (driven through a pipe, --script -) waits for
// its next command; they must be the screenshot's bytes, plus the overlay. Two MPI ranks must show
// what one rank shows.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>

#include <gtest/gtest.h>

#include "common/file_util.h"
#include "support/test_support.h"
#include "viewer/overlay.h"
#include "viewer_runner.h"

namespace sm::test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Top-left of the window on Xvfb's black root (-br): the first pixel that is not black.
bool findWindow(const scene::Image& screen, int& x0, int& y0) {
  x0 = screen.width;
  y0 = screen.height;
  for (int y = 0; y < screen.height; ++y)
    for (int x = 0; x < screen.width; ++x)
      if (glm::vec3(screen.at(x, y)) != glm::vec3(0.0f)) {
        x0 = std::min(x0, x);
        y0 = std::min(y0, y);
      }
  return x0 < screen.width;
}

struct ScreenCheck {
  int differentBelowOverlay = -1;  // pixels below the overlay that differ from the screenshot
  int whiteInOverlay = 0;          // text pixels in the overlay's rows
  int whiteInShot = 0;             // the same count in the screenshot (no overlay there)
};

ScreenCheck compareWindow(const scene::Image& screen, const scene::Image& shot, int overlayRows) {
  ScreenCheck c;
  int x0, y0;
  if (!findWindow(screen, x0, y0) || x0 + shot.width > screen.width ||
      y0 + shot.height > screen.height)
    return c;
  c.differentBelowOverlay = 0;
  for (int y = 0; y < shot.height; ++y)
    for (int x = 0; x < shot.width; ++x) {
      const glm::vec4 s = screen.at(x0 + x, y0 + y), v = shot.at(x, y);
      if (y >= overlayRows) {
        c.differentBelowOverlay += glm::vec3(s) != glm::vec3(v);
      } else {
        c.whiteInOverlay += glm::vec3(s) == glm::vec3(1.0f);
        c.whiteInShot += glm::vec3(v) == glm::vec3(1.0f);
      }
    }
  return c;
}

void waitFor(const std::function<bool()>& done, double seconds, const char* what) {
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  while (!done()) {
    ASSERT_LT(Clock::now(), end) << "gave up waiting for " << what;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
}

TEST(ViewerWindow, WhatReachesTheScreenIsTheScreenshotPlusOverlay) {
  const std::string dir = outputDir("ViewerWindow.Screen"), fb = dir + "/fb";
  const std::string mesh = generateTestMesh(dir), shot = dir + "/shown.png";
  fs::remove_all(fb);
  fs::create_directories(fb);
  fs::remove(shot);
  const std::string command = xvfbRun("-screen 0 320x240x24 -br -fbdir " + fb) + " " +
                              shellmarch() + " view " + quote(mesh) +
                              " --field vortex --size 256x192 --script - --print-camera > " +
                              quote(dir + "/view.out") + " 2> " + quote(dir + "/view.err");
  std::FILE* viewer = popen(command.c_str(), "w");
  ASSERT_NE(viewer, nullptr);
  std::fputs(("drag left 30 10 2\nframe 2\nscreenshot " + shot + "\nframe\n").c_str(), viewer);
  std::fflush(viewer);
  // The viewer has presented the screenshot's frame once the file exists, and then waits on the
  // pipe: its window keeps showing that frame.
  waitFor([&] { return fileExists(shot); }, 300, "the screenshot");
  const scene::Image expected = scene::readPng(shot);
  const int overlayRows = view::overlayBox({"", "", "", ""}, 1).height;
  ScreenCheck check;
  scene::Image screen;
  waitFor(
      [&] {
        screen = readXwd(fb + "/Xvfb_screen0");
        check = compareWindow(screen, expected, overlayRows);
        return check.differentBelowOverlay == 0;
      },
      60, "the window to show the screenshot");
  scene::writePngRgba(dir + "/screen.png", screen);  // what the test saw, to look at
  std::fputs("quit\n", viewer);
  const int status = pclose(viewer);
  EXPECT_EQ(status, 0) << readTextFile(dir + "/view.err");
  std::printf(
      "window pixels below the overlay unlike the screenshot: %d of %d; overlay text pixels %d\n",
      check.differentBelowOverlay, expected.width * (expected.height - overlayRows),
      check.whiteInOverlay);
  EXPECT_GT(check.whiteInOverlay, 200);  // the overlay's text is on screen
  EXPECT_EQ(check.whiteInShot, 0);       // and not in the screenshot
  const nlohmann::json j = lastJson(readTextFile(dir + "/view.out"));
  EXPECT_EQ(j["frames"], 3);
  EXPECT_EQ(j["validation_errors"], 0);
  EXPECT_EQ(readTextFile(dir + "/view.err").find("validation error"), std::string::npos);
}

// The same session on one rank and on two: the same final state, and the same image up to the
// rounding of compositing a ray's samples in one fragment or in several (one per rank).
TEST(ViewerMpi, TwoRanksShowWhatOneRankShows) {
  const std::string dir = outputDir("ViewerMpi.TwoRanks");
  const std::string mesh = generateTestMesh(dir);
  const std::string script = writeFile(
      dir, "session.txt",
      "drag left 50 -15 3\nscroll 1\nframe\ndrag middle -8 4\nkey right\nframe 2\nquit\n");
  auto view = [&](const std::string& launcher, const std::string& tag) {
    const std::string shot = dir + "/" + tag + ".png";
    CommandResult r =
        runCommand(xvfbRun() + " " + launcher + shellmarch() + " view " + quote(mesh) +
                       " --field vortex --size 160x120 --script " + quote(script) +
                       " --screenshot " + quote(shot) + " --print-camera",
                   dir, tag);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find("validation error"), std::string::npos) << r.err;
    return std::make_pair(lastJson(r.out), scene::readPng(shot));
  };
  auto [one, oneImage] = view("", "one-rank");
  auto [two, twoImage] = view(mpiexec() + " -n 2 --oversubscribe ", "two-ranks");
  EXPECT_EQ(one["eye"], two["eye"]);
  EXPECT_EQ(one["at"], two["at"]);
  EXPECT_EQ(one["time"], 1);
  EXPECT_EQ(two["time"], 1);
  EXPECT_EQ(two["frames"], 3);
  EXPECT_EQ(one["ranks"], 1);
  EXPECT_EQ(two["ranks"], 2);
  // Each rank sends its own fragments: more of them per pixel than one rank's single segments.
  EXPECT_GT(two["fragments_per_pixel"].get<double>(), one["fragments_per_pixel"].get<double>());
  const scene::ImageError e = scene::compareImages(oneImage, twoImage);
  std::printf("2 ranks vs 1 rank: RMSE %.3g, max abs %.3g (8-bit steps %.1f)\n", e.rmse, e.maxAbs,
              e.maxAbs * 255);
  EXPECT_LE(e.maxAbs, 2.0 / 255 + 1e-6);
  EXPECT_LE(e.rmse, 0.5 / 255);
  EXPECT_GT(pixelsUnlike(oneImage, {0.1f, 0.1f, 0.12f}),
            size_t(oneImage.width * oneImage.height / 10));
}

// While rank 0 holds each played step for 1/F s, rank 1 waits for the next frame's state: asleep,
// not spinning in the broadcast as a blocking MPI broadcast would (its thread's CPU time then
// equals the wait).
TEST(ViewerMpi, RanksWaitingForRankZeroSleep) {
  const std::string dir = outputDir("ViewerMpi.Waiting");
  const std::string mesh = generateTestMesh(dir);
  CommandResult r =
      runCommand("env -u DISPLAY -u WAYLAND_DISPLAY " + mpiexec() + " -n 2 --oversubscribe " +
                     shellmarch() + " view " + quote(mesh) +
                     " --field vortex --size 32x24 --headless --print-camera --play "
                     "--frames 8 --fps 4",
                 dir, "paced");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = lastJson(r.out);
  const double waited = j["other_ranks_state_wait_ms"].get<double>();
  const double cpu = j["other_ranks_state_wait_cpu_ms"].get<double>();
  std::printf("rank 1 waited %.0f ms for the state, %.1f ms of CPU time\n", waited, cpu);
  EXPECT_GE(waited, 1000.0);  // seven steps held 250 ms each
  EXPECT_LE(cpu, 0.2 * waited);
}

}  // namespace
}  // namespace sm::test
