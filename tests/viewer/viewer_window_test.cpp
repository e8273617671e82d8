// The viewer end to end, as a user runs it: a window under Xvfb (xvfb-run), driven by a script,
// compared with `shellmarch render` at the camera the viewer ends with; what reaches the screen
// (Xvfb's framebuffer) compared with the screenshot; headless use without a display.
// Every run has the validation layer on (SHELLMARCH_VALIDATION=1 from ctest) and must report
// no error.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <thread>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "common/file_util.h"
#include "gen/generate.h"
#include "io/mesh_io.h"
#include "support/test_support.h"
#include "viewer_checks.h"
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
  // "Coarser" stops at the data's diagonal, past which most rays would take no sample.
  std::string coarser = "frame\n";
  for (int i = 0; i < 60; ++i) coarser += "key ]\n";  // 1.25^60: far past the data
  const std::string coarse = writeFile(dir, "coarser.txt", coarser + "frame\nquit\n");
  CommandResult info = runCommand(shellmarch() + " info " + quote(mesh) + " --json", dir, "info");
  const nlohmann::json b = nlohmann::json::parse(info.out)["bounds"];
  double d2 = 0;
  for (int k = 0; k < 3; ++k)
    d2 += std::pow(b["hi"][k].get<double>() - b["lo"][k].get<double>(), 2);
  EXPECT_NEAR(run(" --script " + quote(coarse), "coarser"), std::sqrt(d2), 1e-9 * std::sqrt(d2));
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

// Closing the viewer, or jumping to another step, while a step is read ahead stops that read
// instead of waiting for it to end. The fault holds every read ahead until it is stopped or a
// minute passes, so the viewer can end quickly, with its reads ahead counted as stopped, only
// when both stop them (without the stop it would end after two minutes, none stopped).
TEST(ViewerHeadless, ClosingOrJumpingStopsTheStepReadAhead) {
  const std::string dir = outputDir("ViewerHeadless.StopReadAhead");
  const std::string mesh = generateTestMesh(dir);
  const std::string view = headlessView(mesh, "32x24");
  // Space plays step 0 and reads 1 ahead; left jumps to step 2 (3 steps) while 1 is still being
  // read, and reads 0 ahead; quit comes while 0 is being read.
  const std::string script =
      writeFile(dir, "jump.txt", "key space\nframe\nkey left\nframe\nquit\n");
  const auto start = std::chrono::steady_clock::now();
  CommandResult r = runCommand("SHELLMARCH_FAULT=at=read-ahead,action=stall " + view +
                                   "--range 0,1 --script " + quote(script),
                               dir, "jump");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("validation error"), std::string::npos) << r.err;
  // Both reads ahead were held (and so were running when stopped).
  size_t held = 0;
  for (size_t at = r.err.find("stall on rank 0 in a read ahead"); at != std::string::npos;
       at = r.err.find("stall on rank 0 in a read ahead", at + 1))
    ++held;
  EXPECT_EQ(held, 2u) << r.err;
  const nlohmann::json j = lastJson(r.out);
  EXPECT_EQ(j["stopped_reads"], 2) << r.out;
  EXPECT_EQ(j["time"], 2);
  EXPECT_EQ(j["prefetched_steps"], 0);
  EXPECT_LT(seconds, 30.0) << "a held read was waited for";
}

// Every field steps through its own time steps, not only the one the viewer started with, and its
// colours span all of them. (Once, after the first field, preparation having taken the points out
// of the loaded mesh made every rank count the others as one step: stuck at step 0, coloured by
// its range.)
TEST(ViewerHeadless, EveryFieldStepsThroughItsTimeSteps) {
  const std::string dir = outputDir("ViewerHeadless.FieldSteps");
  const std::string mesh = generateTestMesh(dir);
  CommandResult info = runCommand(shellmarch() + " info " + quote(mesh) + " --json", dir, "info");
  ASSERT_EQ(info.status, 0) << info.err;
  const nlohmann::json fields = nlohmann::json::parse(info.out)["fields"];
  const std::string script =
      writeFile(dir, "steps.txt", "key f shift\nframe\nkey right\nframe\nkey right\nframe\nquit\n");
  CommandResult r =
      runCommand(headlessView(mesh, "32x24") + "--script " + quote(script), dir, "view");
  expectCleanRun(r);
  const nlohmann::json j = lastJson(r.out);
  ASSERT_NE(j["field"], "vortex");
  EXPECT_EQ(j["time"], 2);
  for (const auto& f : fields)
    if (f["name"] == j["field"]) {
      EXPECT_EQ(f["steps"], 3);
      EXPECT_NEAR(j["range"][0].get<double>(), f["range"][0].get<double>(), 1e-5);
      EXPECT_NEAR(j["range"][1].get<double>(), f["range"][1].get<double>(), 1e-5);
    }
}

// A file of cell data alone (a cell-centred solver's output) is browsed like point data: the
// viewer opens without --field on its first array and the field key goes through the others, each
// streamed a step at a time and ranged over its steps as `info` ranges it, on one rank and on two
// that share the pieces' points.
TEST(ViewerHeadless, CellDataIsBrowsedLikePointData) {
  const std::string dir = outputDir("ViewerHeadless.CellData");
  mesh::UnstructuredMesh m = gen::cube(gen::CubeSplit::Hex, 4);
  for (int t = 0; t < mesh::kNumCellTypes; ++t) {
    const uint32_t nv = mesh::numVerts(mesh::kAllCellTypes[t]);
    for (size_t e = 0; e < m.clusters[t].size(); ++e)
      m.clusters[t][e] = int32_t(m.points[m.cells[t][e * nv]].x * 2.99);  // 3 slabs
  }
  for (int f = 0; f < 2; ++f) {
    mesh::CellField cf{f == 0 ? "pressure" : "density", {}};
    for (int s = 0; s < (f == 0 ? 1 : 3); ++s) {
      auto& perType = cf.steps.emplace_back();
      for (int t = 0; t < mesh::kNumCellTypes; ++t)
        for (size_t e = 0; e < m.clusters[t].size(); ++e)
          perType[t].push_back(float((f + 1) * (e % 7) + 10 * s));
    }
    m.cellFields.push_back(std::move(cf));
  }
  const std::string mesh = dir + "/cells.pvtu";
  io::writePvtu(mesh, m);
  CommandResult info =
      runCommand(shellmarch() + " info " + quote(mesh) + " --field density --json", dir, "info");
  ASSERT_EQ(info.status, 0) << info.err;
  const nlohmann::json density = nlohmann::json::parse(info.out)["fields"][0];
  ASSERT_EQ(density["steps"], 3);
  const std::string script =
      writeFile(dir, "keys.txt", "frame\nkey f\nframe\nkey right\nframe\nquit\n");
  for (const char* launch : {"", "mpi"}) {
    SCOPED_TRACE(*launch ? "2 ranks" : "1 rank");
    const std::string view = std::string("env -u DISPLAY -u WAYLAND_DISPLAY ") +
                             (*launch ? mpiexec() + " -n 2 --oversubscribe " : "") + shellmarch() +
                             " view " + quote(mesh) +
                             " --size 32x24 --headless --print-camera --script " + quote(script);
    CommandResult r = runCommand(view, dir, *launch ? "view-mpi" : "view");
    expectCleanRun(r);
    const nlohmann::json j = lastJson(r.out);
    EXPECT_EQ(j["field"], "density");
    EXPECT_EQ(j["time"], 1);
    EXPECT_EQ(j["range_steps_read"], 1 + 3);  // pressure's step, then density's
    EXPECT_NEAR(j["range"][0].get<double>(), density["range"][0].get<double>(), 1e-5);
    EXPECT_NEAR(j["range"][1].get<double>(), density["range"][1].get<double>(), 1e-5);
  }
}

// A new field's colour range is read over all its steps before its first frame; a close that
// comes meanwhile (the fault stands for the window's close button, pressed as the pass starts)
// stops the pass before its next step and ends the viewer, on every rank, instead of letting it
// read the field to the end first. Without the close the pass reads the field's three steps and
// the frame shows it.
TEST(ViewerHeadless, ClosingDuringANewFieldsRangePassStopsIt) {
  const std::string dir = outputDir("ViewerHeadless.RangePass");
  const std::string mesh = generateTestMesh(dir);
  const std::string script = writeFile(dir, "field.txt", "key f\nframe\nframe\nquit\n");
  const std::string view = headlessView(mesh, "32x24") + "--range 0,1 --script " + quote(script);
  CommandResult r = runCommand(view, dir, "read");
  expectCleanRun(r);
  nlohmann::json j = lastJson(r.out);
  EXPECT_EQ(j["range_pass_stopped"], false);
  EXPECT_EQ(j["range_steps_read"], 3);
  EXPECT_NE(j["field"], "vortex");

  for (const char* launch : {"", "mpi"}) {
    SCOPED_TRACE(*launch ? "2 ranks" : "1 rank");
    // The fault on rank 0 only: rank 1 learns of the close through the pass's collective.
    std::string command = "SHELLMARCH_FAULT=at=range-pass,rank=0,action=close " + view;
    if (*launch)
      command =
          "SHELLMARCH_FAULT=at=range-pass,rank=0,action=close env -u DISPLAY -u "
          "WAYLAND_DISPLAY " +
          mpiexec() + " -n 2 --oversubscribe " + shellmarch() + " view " + quote(mesh) +
          " --field vortex --size 32x24 --headless --print-camera --range 0,1 --script " +
          quote(script);
    r = runCommand(command, dir, *launch ? "stopped-mpi" : "stopped");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find("validation error"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("close on rank 0 in a range pass"), std::string::npos) << r.err;
    j = lastJson(r.out);
    EXPECT_EQ(j["range_pass_stopped"], true);
    EXPECT_EQ(j["range_steps_read"], 0);
    EXPECT_EQ(j["field"], "vortex");  // the new field's frame was never made
  }
}

// The field key pressed while a new field's range pass reads its steps goes on to the next field
// without waiting for the pass to finish: the fault presses it as the pass starts (once), so the
// script's one f and the injected one end on the field two f's reach, having read only that
// field's steps, on every rank.
TEST(ViewerHeadless, TheFieldKeyDuringARangePassGoesOnWithoutIt) {
  const std::string dir = outputDir("ViewerHeadless.RangePassSkipped");
  const std::string mesh = generateTestMesh(dir);
  const std::string twice = writeFile(dir, "twice.txt", "key f\nframe\nkey f\nframe\nquit\n");
  CommandResult r = runCommand(headlessView(mesh, "32x24") + "--range 0,1 --script " + quote(twice),
                               dir, "twice");
  expectCleanRun(r);
  const nlohmann::json reference = lastJson(r.out);
  ASSERT_EQ(reference["range_steps_read"], 6);  // the new fields' three steps (--range: vortex's)
  ASSERT_EQ(reference["range_passes_skipped"], 0);

  const std::string once = writeFile(dir, "once.txt", "key f\nframe\nframe\nquit\n");
  for (const char* launch : {"", "mpi"}) {
    SCOPED_TRACE(*launch ? "2 ranks" : "1 rank");
    const std::string command =
        "SHELLMARCH_FAULT=at=range-pass,rank=0,action=next-field env -u DISPLAY -u "
        "WAYLAND_DISPLAY " +
        (*launch ? mpiexec() + " -n 2 --oversubscribe " : std::string()) + shellmarch() + " view " +
        quote(mesh) +
        " --field vortex --size 32x24 --headless --print-camera --range 0,1 --script " +
        quote(once);
    r = runCommand(command, dir, *launch ? "skipped-mpi" : "skipped");
    expectCleanRun(r);
    EXPECT_NE(r.err.find("next-field on rank 0 in a range pass"), std::string::npos) << r.err;
    const nlohmann::json j = lastJson(r.out);
    EXPECT_EQ(j["field"], reference["field"]);
    EXPECT_EQ(j["range"], reference["range"]);
    EXPECT_EQ(j["range_passes_skipped"], 1);
    EXPECT_EQ(j["range_pass_stopped"], false);
    EXPECT_EQ(j["range_steps_read"], 3);  // the skipped field's pass read none of its steps
  }
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
