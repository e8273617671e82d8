// Scripts and input handling, without a window: a script's commands become the events a user's
// mouse and keys would, frame by frame, and those events change the state as the controls say.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "common/error.h"
#include "scene/bitmap_font.h"
#include "viewer/input.h"
#include "viewer/overlay.h"
#include "viewer/script.h"

namespace sm::view {
namespace {

using T = InputEvent::Type;

ViewChoices choices() {
  return {{"pressure", "vortex", "density"}, {"viridis", "jet"}};
}

ViewState startState() {
  ViewState s;
  s.setCamera({{4, -3, 1}, {0, 0, 0}, {0, 0, 1}, 30.0});
  s.width = 200;
  s.height = 100;
  s.dt = 0.1;
  return s;
}

// Plays the whole script into a handler; returns the frames it took.
int play(const std::string& text, InputHandler& h, ViewState& s, LocalRequests& local) {
  Script script = Script::parse(text, "test.txt");
  std::vector<InputEvent> events;
  int frames = 0;
  while (script.nextFrame(events)) {
    for (const auto& e : events) h.apply(e, s, local);
    events.clear();
    ++frames;
  }
  return frames;
}

TEST(ViewerScript, FramesCarryTheirInput) {
  Script s = Script::parse(
      "# orbit, then a step\n"
      "drag left 10 -4 2\n"
      "frame\n"
      "key right\n"
      "frame 3\n"
      "screenshot a.png   # trailing input is one more frame\n",
      "test.txt");
  std::vector<InputEvent> e;
  ASSERT_TRUE(s.nextFrame(e));
  ASSERT_EQ(e.size(), 5u);  // move to the start, press, two moves, release
  EXPECT_EQ(e[1].type, T::Press);
  EXPECT_EQ(e[3].type, T::Move);
  EXPECT_DOUBLE_EQ(e[3].x, 10.0);
  EXPECT_DOUBLE_EQ(e[3].y, -4.0);
  EXPECT_EQ(e[4].type, T::Release);
  e.clear();
  ASSERT_TRUE(s.nextFrame(e));
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].key, Key::NextStep);
  for (int i = 0; i < 2; ++i) {
    e.clear();
    ASSERT_TRUE(s.nextFrame(e));
    EXPECT_TRUE(e.empty());
  }
  e.clear();
  ASSERT_TRUE(s.nextFrame(e));
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].path, "a.png");
  EXPECT_FALSE(s.nextFrame(e));
}

TEST(ViewerScript, ErrorsNameTheFileAndLine) {
  try {
    Script::parse("frame\ndrag sideways 1 2\n", "moves.txt");
    FAIL() << "no error";
  } catch (const Error& err) {
    EXPECT_NE(std::string(err.what()).find("moves.txt:2"), std::string::npos) << err.what();
  }
  EXPECT_THROW(Script::parse("key nosuchkey\n", "k"), Error);
  EXPECT_THROW(Script::parse("frame 0\n", "f"), Error);
  EXPECT_THROW(Script::parse("resize 10\n", "r"), Error);
  EXPECT_THROW(Script::parse("press left ctrl\n", "p"), Error);
}

TEST(ViewerInput, DragsOrbitPanAndZoom) {
  InputHandler h(startState().camera(), choices());
  LocalRequests local;
  ViewState orbit = startState(), pan = startState(), zoom = startState();
  const double d0 = glm::length(orbit.eye - orbit.at);
  play("drag left 30 12 3\n", h, orbit, local);
  EXPECT_NEAR(glm::length(orbit.eye - orbit.at), d0, 1e-12);
  EXPECT_EQ(orbit.at, startState().at);
  EXPECT_GT(glm::length(orbit.eye - startState().eye), 0.1);

  play("drag middle 5 5\ndrag left -5 -5 1 shift\n", h, pan, local);  // pans there and back
  EXPECT_NEAR(glm::length(pan.eye - startState().eye), 0.0, 1e-12);
  play("drag left 7 0 shift\n", h, pan, local);
  EXPECT_NEAR(glm::length((pan.eye - pan.at) - (startState().eye - startState().at)), 0.0, 1e-12);
  EXPECT_GT(glm::length(pan.at), 0.01);

  play("drag right 0 -20\nscroll 2\n", h, zoom, local);
  EXPECT_LT(glm::length(zoom.eye - zoom.at), d0);
  EXPECT_NEAR(glm::dot(glm::normalize(zoom.eye - zoom.at), glm::normalize(startState().eye)), 1.0,
              1e-12);
}

TEST(ViewerInput, MovesWithoutAButtonDoNothing) {
  InputHandler h(startState().camera(), choices());
  LocalRequests local;
  ViewState s = startState();
  play("move 10 10\nmove 50 70\nrelease left\nmove 0 0\n", h, s, local);
  EXPECT_EQ(s.eye, startState().eye);
}

TEST(ViewerInput, KeysChangeStepFieldColormapOpacitySamplingAndPlay) {
  InputHandler h(startState().camera(), choices());
  LocalRequests local;
  ViewState s = startState();
  play(
      "key right\nkey right\nkey left\nkey f\nkey f\nkey f\nkey f shift\nkey c\nkey c\nkey c\n"
      "key up\nkey up\nkey down\nkey [\nkey [\nkey ]\nkey s\nkey o\n",
      h, s, local);
  EXPECT_EQ(s.step, 1);
  EXPECT_EQ(s.field, 2);     // 0 -> 1 -> 2 -> 0 (wraps) -> 2 (back, wraps)
  EXPECT_EQ(s.colormap, 1);  // three steps through two maps
  EXPECT_DOUBLE_EQ(s.opacityScale, InputHandler::kOpacityFactor);
  EXPECT_DOUBLE_EQ(s.dt, 0.1 / InputHandler::kStepFactor);
  EXPECT_EQ(local.screenshots.size(), 1u);
  EXPECT_TRUE(local.toggleOverlay);
  EXPECT_EQ(s.quit, 0u);
  EXPECT_EQ(s.playing, 0u);
  play("key space\n", h, s, local);
  EXPECT_EQ(s.playing, 1u);
  EXPECT_EQ(s.step, 1);  // the viewer advances a playing state, once per frame
  play("key space\n", h, s, local);
  EXPECT_EQ(s.playing, 0u);
  play("drag left 40 0\nkey r\n", h, s, local);  // reset view
  EXPECT_EQ(s.eye, startState().eye);
  play("key escape\n", h, s, local);
  EXPECT_EQ(s.quit, 1u);
}

// The cut (x): a plane through the point looked at, facing away from the camera, fixed in the
// world once made; . and , move it farther and nearer by a fiftieth of the home distance; shift+x
// keeps the near half instead; no cut while the job's --clip planes leave no room for one.
TEST(ViewerInput, TheCutKeysPlaceAndMoveAClipPlane) {
  InputHandler h(startState().camera(), choices());
  LocalRequests local;
  ViewState s = startState();
  play("key .\n", h, s, local);  // no cut yet: nothing to move
  EXPECT_EQ(s.cut, 0u);
  play("key x\n", h, s, local);
  ASSERT_EQ(s.cut, 1u);
  EXPECT_EQ(s.cutPoint, s.at);
  const glm::dvec3 away = glm::normalize(s.at - s.eye);
  EXPECT_NEAR(glm::distance(s.cutNormal, away), 0.0, 1e-12);
  const double step = InputHandler::kCutStepFraction * glm::length(s.eye - s.at);
  play("key .\nkey .\nkey ,\n", h, s, local);
  EXPECT_NEAR(glm::distance(s.cutPoint, s.at + step * away), 0.0, 1e-12);
  const glm::dvec3 placed = s.cutPoint, normal = s.cutNormal;
  play("drag left 40 0\n", h, s, local);  // orbiting leaves the cut where it is
  EXPECT_EQ(s.cutPoint, placed);
  EXPECT_EQ(s.cutNormal, normal);
  play("key x\n", h, s, local);
  EXPECT_EQ(s.cut, 0u);
  play("key x shift\nkey .\n", h, s, local);  // the near half kept; . still moves it away
  const glm::dvec3 view = glm::normalize(s.at - s.eye);
  EXPECT_NEAR(glm::dot(s.cutNormal, view), -1.0, 1e-12);
  EXPECT_NEAR(glm::distance(s.cutPoint, s.at + step * view), 0.0, 1e-12);
  ViewChoices full = choices();
  full.cutAvailable = false;
  InputHandler none(startState().camera(), full);
  ViewState t = startState();
  play("key x\n", none, t, local);
  EXPECT_EQ(t.cut, 0u);
}

// g turns the log scale on and off (for every rank: it is part of the broadcast state), and the
// controls list it.
TEST(ViewerInput, TheGKeyTogglesTheLogScale) {
  InputHandler h(startState().camera(), choices());
  LocalRequests local;
  ViewState s = startState();
  EXPECT_EQ(s.logScale, 0u);
  play("key g\n", h, s, local);
  EXPECT_EQ(s.logScale, 1u);
  play("key g\n", h, s, local);
  EXPECT_EQ(s.logScale, 0u);
  EXPECT_EQ(keyFromName("g"), Key::ToggleLogScale);
  EXPECT_FALSE(keyRepeats(Key::ToggleLogScale));
  EXPECT_NE(controlsHelp().find("  g  "), std::string::npos);
}

// p switches to a parallel projection showing `at` at the size it had, and back; the wheel then
// changes the parallel scale.
TEST(ViewerInput, ThePKeyTogglesTheProjection) {
  InputHandler h(startState().camera(), choices());
  LocalRequests local;
  ViewState s = startState();
  const double d = glm::length(s.eye - s.at);
  EXPECT_EQ(s.parallel, 0u);
  play("key p\n", h, s, local);
  EXPECT_EQ(s.parallel, 1u);
  EXPECT_NEAR(s.parallelScale, d * std::tan(s.fovyDeg * std::numbers::pi / 360), 1e-12);
  const double scale = s.parallelScale;
  play("scroll 1\n", h, s, local);
  EXPECT_NEAR(s.parallelScale, 0.9 * scale, 1e-12);
  EXPECT_NEAR(glm::length(s.eye - s.at), d, 1e-12);
  play("key p\n", h, s, local);
  EXPECT_EQ(s.parallel, 0u);
  EXPECT_NEAR(glm::length(s.eye - s.at), 0.9 * d, 1e-12);
  EXPECT_EQ(keyFromName("p"), Key::ToggleProjection);
  EXPECT_FALSE(keyRepeats(Key::ToggleProjection));
  EXPECT_NE(controlsHelp().find("  p  "), std::string::npos);
}

// Held down, a stepping key steps again with each auto-repeat; space would toggle play on and
// off, so toggles act once per press.
TEST(ViewerInput, HeldKeysRepeatOnlyWhenTheyStep) {
  for (Key k :
       {Key::NextStep, Key::PrevStep, Key::MoreOpaque, Key::LessOpaque, Key::NextField,
        Key::NextColormap, Key::FinerStep, Key::CoarserStep, Key::CutNearer, Key::CutFarther})
    EXPECT_TRUE(keyRepeats(k)) << int(k);
  for (Key k : {Key::TogglePlay, Key::ToggleOverlay, Key::ToggleLegend, Key::Screenshot, Key::Help,
                Key::Quit, Key::ResetView, Key::ToggleCut, Key::None})
    EXPECT_FALSE(keyRepeats(k)) << int(k);
}

TEST(ViewerOverlay, DrawsTheGlyphsInsideItsBox) {
  const int w = 64, h = 32;
  std::vector<uint8_t> img(size_t(w) * h * 4, 100);
  drawOverlay(img, w, h, {"1"}, 2);
  const OverlayBox box = overlayBox({"1"}, 2);
  int white = 0, dark = 0, untouched = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint8_t v = img[(size_t(y) * w + x) * 4];
      const bool inside = x < box.width && y < box.height;
      if (v == 255) {
        ++white;
        EXPECT_TRUE(inside) << x << "," << y;
      } else if (v == 30) {
        ++dark;
      } else if (v == 100) {
        ++untouched;
        EXPECT_FALSE(inside) << x << "," << y;
      }
    }
  int dots = 0;
  for (int r = 0; r < 7; ++r) dots += __builtin_popcount(scene::glyph('1')[r]);
  EXPECT_EQ(white, dots * 4);  // scale 2: four pixels per dot
  EXPECT_EQ(white + dark, box.width * box.height);
  EXPECT_EQ(untouched, w * h - box.width * box.height);
  EXPECT_NE(scene::glyph('a'), scene::glyph('A'));  // the overlay shows names in their case
  EXPECT_EQ(scene::glyph('\x01'), scene::glyph('?'));
}

}  // namespace
}  // namespace sm::view
